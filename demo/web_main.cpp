// fluid-demo in a browser page (emscripten, WebGL2 through GLFW): the same game as the desktop's
// (app.h) on the GLFW platform layer, its frames driven by the page's animation callback.
//
// The page (demo/web/index.html) passes the address's query as arguments:
//   ?level=NAME            the level to start on (default the playlist's first)
//   &script=FILE&frames=N  play FILE's scripted input for N frames of one step each, then
//                          print the summary line (with the state's hash) and stop
//   &screenshot=FILE       with frames: save the last frame as a PNG in the page's file system
//   &record=FILE           write the player's input down as a script in the page's file system
//                          (one step per frame; with frames, the player's input is taken and
//                          the game ends after them with the summary line)
// Levels are packed at /levels; F5 / F9 saves live in /saves, which the page keeps in the
// browser's IndexedDB.
#include "bench/command_line.h"

#include "demo/app.h"
#include "demo/level_list.h"
#include "demo/script.h"

#include <CLI/CLI.hpp>

#include <emscripten/emscripten.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <string>

namespace {

std::unique_ptr<fluid::demo::GameRunner> g_game;

// Tells the page the game is over (Module.fluidExit(status), when the page defines it).
EM_JS(void, announceExit, (int status), {
    if (Module.fluidExit) {
        Module.fluidExit(status);
    }
});

// Counts the frames the game has drawn in `Module.fluidFramesDrawn` (0 until the first): what
// a screenshot of the page waits for (tests/web/play.mjs --frames-drawn, docs/web.md).
EM_JS(void, noteFrameDrawn, (), {
    Module.fluidFramesDrawn = (Module.fluidFramesDrawn || 0) + 1;
});

void frame() {
    if (g_game && g_game->frame()) {
        noteFrameDrawn();
        return;
    }
    if (g_game) {
        const int status = g_game->finish();
        g_game.reset();
        emscripten_cancel_main_loop();
        std::fflush(stdout);
        announceExit(status);
    }
}

} // namespace

int main(int argc, char** argv) {
    using namespace fluid::demo;
    CLI::App app{"fluid-demo in a browser page"};
    std::string level, scriptPath, screenshot, record;
    uint32_t frames = 0;
    app.add_option("--level", level, "Level to start on (a name from /levels)");
    app.add_option("--script", scriptPath, "Scripted input to play (docs/demo.md)");
    app.add_option("--frames", frames, "With --script: frames to play, then stop")
        ->check(CLI::Range(1u, 1000000u));
    app.add_option("--screenshot", screenshot, "With --frames: PNG of the last frame");
    app.add_option("--record", record, "Write the input down as a script (docs/demo.md)");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        announceExit(status);
        return status;
    }
    GameOptions options;
    try {
        options.levels = listLevels("/levels");
        if (!scriptPath.empty()) {
            options.script = readScript(scriptPath);
            options.scriptPath = scriptPath;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fluid-demo: %s\n", e.what());
        announceExit(2);
        return 2;
    }
    if (!level.empty()) {
        options.first = findLevel(options.levels, level);
        if (options.first < 0) {
            std::fprintf(stderr, "fluid-demo: no level '%s' in /levels\n", level.c_str());
            announceExit(2);
            return 2;
        }
    }
    options.frames = frames;
    options.screenshot = screenshot;
    options.record = record;
    options.workers = 1; // a build without threads (docs/web.md)
    options.saveDir = "/saves";
    options.screenshotDir = "/screenshots";
    options.size = {1280, 720};
    g_game = std::make_unique<GameRunner>(options);
    if (!g_game->start()) {
        g_game->finish();
        g_game.reset();
        announceExit(1);
        return 1;
    }
    // The page's animation callback plays the frames; main returns and the runtime stays.
    emscripten_set_main_loop(frame, 0, false);
    return 0;
}
