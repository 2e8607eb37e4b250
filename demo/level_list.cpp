// fluid-demo — the playlist.
#include "demo/level_list.h"

#include <fluid/error.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace fluid::demo {
namespace {

// The level's "name", read without building it (the menu lists every level at start-up).
std::string titleOf(const std::filesystem::path& path) {
    std::ifstream in(path);
    const nlohmann::json doc = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (doc.is_object() && doc.contains("name") && doc["name"].is_string()) {
        return doc["name"].get<std::string>();
    }
    return path.stem().string();
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) {
        return {};
    }
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

} // namespace

std::vector<LevelFile> listLevels(const std::string& directory) {
    namespace fs = std::filesystem;
    const fs::path dir(directory);
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        throw Error("fluid-demo: levels directory '" + directory + "' does not exist");
    }
    std::vector<LevelFile> levels;
    std::set<std::string> listed;
    const fs::path playlist = dir / "playlist.txt";
    if (fs::exists(playlist)) {
        std::ifstream in(playlist);
        std::string line;
        for (int number = 1; std::getline(in, line); ++number) {
            const std::string stem = trim(line.substr(0, line.find('#')));
            if (stem.empty()) {
                continue;
            }
            const fs::path file = dir / (stem + ".json");
            if (!fs::exists(file)) {
                throw Error(playlist.string() + ":" + std::to_string(number) + ": level '" + stem +
                            "' does not exist (expected " + file.string() + ")");
            }
            if (listed.insert(stem).second) {
                levels.push_back({stem, file.string(), titleOf(file)});
            }
        }
    }
    std::vector<fs::path> others;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".json" && !listed.count(entry.path().stem().string())) {
            others.push_back(entry.path());
        }
    }
    std::sort(others.begin(), others.end());
    for (const auto& file : others) {
        levels.push_back({file.stem().string(), file.string(), titleOf(file)});
    }
    if (levels.empty()) {
        throw Error("fluid-demo: no level files (*.json) in '" + directory + "'");
    }
    return levels;
}

int findLevel(const std::vector<LevelFile>& levels, const std::string& nameOrPath) {
    const std::string stem = std::filesystem::path(nameOrPath).stem().string();
    for (std::size_t i = 0; i < levels.size(); ++i) {
        if (levels[i].stem == nameOrPath || levels[i].stem == stem) {
            return int(i);
        }
    }
    return -1;
}

} // namespace fluid::demo
