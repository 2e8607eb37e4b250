// fluid-demo — water and yoghurt in gravity and zero-g: the fluid library's game.
//
//   fluid-demo [--level NAME]                 play (the window opens on NAME, default the first)
//   fluid-demo --level NAME --frames N --screenshot FILE [--size WxH] [--view VIEW]
//                                             headless: step N frames, save a PNG, exit
//   fluid-demo --level all --view all --frames N --screenshot-dir DIR
//                                             every level in every view (tests, docs)
//   fluid-demo --level NAME --record FILE [--frames N]
//                                             play, and write the input down as a script
//   fluid-demo --level NAME --script FILE --frames N [--screenshot FILE]
//                                             play a script for N frames, print a summary
#include "bench/command_line.h"

#include "demo/app.h"
#include "demo/headless.h"
#include "demo/level_list.h"
#include "demo/script.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace {

// Exit status for "cannot run here" (ctest's SKIP_RETURN_CODE).
constexpr int kNoDisplay = 77;

bool onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (path == nullptr) {
        return false;
    }
    std::string dirs(path);
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path candidate =
            std::filesystem::path(dirs.substr(start, end - start)) / program;
        if (::access(candidate.c_str(), X_OK) == 0) {
            return true;
        }
        start = end + 1;
    }
    return false;
}

} // namespace

int main(int argc, char** argv) {
    using namespace fluid::demo;
    CLI::App app{"fluid-demo: water and yoghurt in gravity and zero-g. Without --frames it opens "
                 "a window and plays; with --frames it runs headless and saves screenshots."};
    std::string level;
    std::string levelsDir = FLUID_DEMO_LEVELS_DIR;
    uint32_t frames = 0;
    std::string screenshot, screenshotDir;
    std::string size = "1280x720";
    std::string view = "metaballs";
    uint32_t threads = 2;
    uint32_t renderEvery = 0;
    float displayHz = 0.0f;
    bool noHud = false, fullscreen = false;
    std::string scriptPath;
    app.add_option("--level", level,
                   "Level to play: a name from the levels directory (dam_break), a path to a "
                   "level file, or 'all' (headless only)");
    app.add_option("--levels-dir", levelsDir, "Directory of level files and playlist.txt")
        ->capture_default_str();
    app.add_option("--frames", frames, "Run headless: step this many frames, then save")
        ->check(CLI::Range(1u, 1000000u));
    auto* shotFile = app.add_option("--screenshot", screenshot, "PNG file to save (headless)");
    auto* shotDir = app.add_option("--screenshot-dir", screenshotDir,
                                   "Directory for LEVEL-VIEW.png and summary.txt (headless)");
    shotFile->excludes(shotDir);
    app.add_option("--size", size, "Window or image size, WxH pixels")->capture_default_str();
    app.add_option("--view", view, "metaballs, pressure, particles, or all (headless)")
        ->check(CLI::IsMember({"metaballs", "pressure", "particles", "all"}))
        ->capture_default_str();
    app.add_option("--threads", threads, "Simulation worker threads")
        ->check(CLI::Range(1u, 64u))
        ->capture_default_str();
    app.add_option("--render-every", renderEvery,
                   "Headless: also render every K frames while stepping (0 = only at the end)");
    app.add_option("--display-hz", displayHz,
                   "Headless: a display at HZ: level frames paced by 1/HZ s of display time, the "
                   "liquid drawn between the last two (0 = one level frame per frame)")
        ->check(CLI::Range(0.0f, 1000.0f));
    app.add_flag("--no-hud", noHud, "Headless: leave the HUD and level banner out of images");
    app.add_flag("--fullscreen", fullscreen, "Start in fullscreen (F11 toggles)");
    std::string saveDir;
    app.add_option("--save-dir", saveDir,
                   "Where F5 saves the level and F9 loads it (default: $XDG_STATE_HOME/fluid-demo, "
                   "else ~/.local/state/fluid-demo)");
    app.add_option("--script", scriptPath,
                   "Play the game with scripted input (docs/demo.md); with --frames N it runs N "
                   "frames of one step each, prints a summary and exits");
    std::string record;
    app.add_option("--record", record,
                   "Play and write the input down as a script for --script (docs/demo.md): one "
                   "step per frame; with --frames N the game ends after N frames with the summary");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        return status;
    }

    int width = 0, height = 0;
    char tail = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 16 ||
        height < 16 || width > 8192 || height > 8192) {
        std::fprintf(stderr, "fluid-demo: --size '%s' is not WxH with each in [16, 8192] pixels\n",
                     size.c_str());
        return 2;
    }
    const bool scripted = !scriptPath.empty();
    // The game (a window) with a script or a recording; otherwise --frames means headless.
    const bool game = scripted || !record.empty();
    const bool headless = !game && (frames > 0 || !screenshot.empty() || !screenshotDir.empty());
    std::vector<ScriptAction> script;
    if (scripted) {
        try {
            script = readScript(scriptPath);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "fluid-demo: %s\n", e.what());
            return 2;
        }
    }
    if (game && (!screenshotDir.empty() || level == "all" || view != "metaballs")) {
        std::fprintf(stderr, "fluid-demo: --script and --record play one level in the game: "
                             "they take --level NAME, --frames and --screenshot FILE\n");
        return 2;
    }
    if (headless && frames == 0) {
        frames = 120;
    }
    if (headless && screenshot.empty() && screenshotDir.empty()) {
        std::fprintf(stderr,
                     "fluid-demo: --frames needs --screenshot FILE or --screenshot-dir DIR\n");
        return 2;
    }
    if (!headless && (level == "all" || view == "all")) {
        std::fprintf(stderr, "fluid-demo: --level all and --view all are for headless runs "
                             "(with --frames and --screenshot-dir)\n");
        return 2;
    }

    std::vector<LevelFile> levels;
    try {
        levels = listLevels(levelsDir);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    int first = 0;
    std::vector<LevelFile> chosen;
    if (level == "all") {
        chosen = levels;
    } else if (!level.empty()) {
        first = findLevel(levels, level);
        if (first < 0 && std::filesystem::exists(level)) {
            // A file outside the levels directory: play it first, the playlist after it.
            const std::filesystem::path path(level);
            levels.insert(levels.begin(),
                          LevelFile{path.stem().string(), path.string(), path.stem().string()});
            first = 0;
        }
        if (first < 0) {
            std::string names;
            for (const LevelFile& f : levels) {
                names += (names.empty() ? "" : ", ") + f.stem;
            }
            std::fprintf(stderr, "fluid-demo: no level '%s' in %s (levels: %s)\n", level.c_str(),
                         levelsDir.c_str(), names.c_str());
            return 2;
        }
        chosen = {levels[size_t(first)]};
    } else {
        chosen = {levels.front()};
    }

    const char* display = std::getenv("DISPLAY");
    const bool hasDisplay = display != nullptr && *display != '\0';
    if (!hasDisplay && (headless || game)) {
        std::fprintf(stderr,
                     "fluid-demo: no display (DISPLAY is not set); run it under Xvfb:\n"
                     "  xvfb-run -a -s \"-screen 0 1280x720x24 -noreset\" %s ...\n",
                     argv[0]);
        return kNoDisplay;
    }
    if (!hasDisplay) {
        // A server without a screen: show what the game looks like instead of failing. Play
        // every level for three seconds under a virtual display and save the pictures.
        if (!onPath("xvfb-run")) {
            std::fprintf(stderr,
                         "fluid-demo: no display (DISPLAY is not set) and no xvfb-run to make "
                         "one.\nRun it on a desktop, or install xvfb and xauth.\n");
            return 1;
        }
        // The pictures go beside the program (in the build folder), not into the folder it was
        // started from, which may be the source tree.
        const std::filesystem::path selfPath = std::filesystem::read_symlink("/proc/self/exe");
        const std::string self = selfPath.string();
        const std::string shots = (selfPath.parent_path() / "fluid-demo-shots").string();
        std::printf("fluid-demo: no display; playing every level headless under Xvfb. "
                    "Screenshots go to %s/\n",
                    shots.c_str());
        std::fflush(stdout);
        std::vector<std::string> args{"xvfb-run",
                                      "-a",
                                      "-s",
                                      "-screen 0 1280x720x24 -noreset",
                                      self,
                                      "--level",
                                      "all",
                                      "--levels-dir",
                                      levelsDir,
                                      "--frames",
                                      "180",
                                      "--screenshot-dir",
                                      shots};
        std::vector<char*> raw;
        for (std::string& a : args) {
            raw.push_back(a.data());
        }
        raw.push_back(nullptr);
        ::execvp("xvfb-run", raw.data());
        std::perror("fluid-demo: xvfb-run");
        return 1;
    }

    if (headless) {
        if (!screenshot.empty() && (chosen.size() > 1 || view == "all")) {
            std::fprintf(stderr, "fluid-demo: --screenshot FILE takes one level and one view; "
                                 "use --screenshot-dir for several\n");
            return 2;
        }
        HeadlessOptions options;
        options.levels = chosen;
        options.frames = frames;
        options.renderEvery = renderEvery;
        options.displayHz = displayHz;
        options.size = {width, height};
        options.workers = threads;
        options.hud = !noHud;
        options.screenshot = screenshot;
        options.screenshotDir = screenshotDir;
        if (view == "all") {
            options.views = {fluid::gl::View::Metaballs, fluid::gl::View::Pressure,
                             fluid::gl::View::Particles};
        } else {
            options.views = {fluid::gl::viewFromName(view).value_or(fluid::gl::View::Metaballs)};
        }
        return runHeadless(options);
    }

    GameOptions options;
    options.levels = levels;
    options.first = first;
    options.size = {width, height};
    options.workers = threads;
    options.fullscreen = fullscreen;
    options.script = std::move(script);
    options.scriptPath = scriptPath;
    options.frames = frames;
    options.screenshot = screenshot;
    options.record = record;
    if (saveDir.empty()) {
        const char* state = std::getenv("XDG_STATE_HOME");
        const char* home = std::getenv("HOME");
        saveDir = state != nullptr && *state != '\0'
                      ? (std::filesystem::path(state) / "fluid-demo").string()
                  : home != nullptr && *home != '\0'
                      ? (std::filesystem::path(home) / ".local/state/fluid-demo").string()
                      : (std::filesystem::temp_directory_path() / "fluid-demo").string();
    }
    options.saveDir = saveDir;
    return runGame(options);
}
