// fluid-demo — quick saves and screenshot names (see saves.h).
#include "demo/saves.h"

#include "demo/platform.h"

#include <ctime>
#include <exception>
#include <filesystem>

namespace fluid::demo {

std::string QuickSaves::path(const std::string& stem) const {
    return (std::filesystem::path(m_directory) / (stem + ".level")).string();
}

bool QuickSaves::has(const std::string& stem) const {
    return std::filesystem::exists(path(stem));
}

QuickSaves::Result QuickSaves::save(const Session& session) const {
    try {
        std::filesystem::create_directories(m_directory);
        session.save(path(session.file().stem));
        keepFiles();
        return {true, "Saved (F9 goes back to it)"};
    } catch (const std::exception& e) {
        return {false, std::string("Could not save: ") + e.what()};
    }
}

QuickSaves::Result QuickSaves::load(Session& session) const {
    if (!has(session.file().stem)) {
        return {false, "No save of this level yet: F5 saves"};
    }
    try {
        session.restore(path(session.file().stem));
        return {true, "Loaded the save"};
    } catch (const std::exception& e) {
        return {false, std::string("Could not load: ") + e.what()};
    }
}

std::string screenshotPath(const std::string& directory, const std::string& stem) {
    char stamp[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
    return (std::filesystem::path(directory) / ("fluid-" + stem + "-" + stamp + ".png")).string();
}

} // namespace fluid::demo
