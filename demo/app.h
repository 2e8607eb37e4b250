// fluid-demo — the interactive game: window, fixed-step loop, controls, HUD and panels.
#pragma once
#include "demo/level_list.h"
#include "demo/script.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fluid::demo {

/// How the game starts.
struct GameOptions {
    /// The playlist (N / B / 1-9 / Esc move through it).
    std::vector<LevelFile> levels;
    /// Index of the first level in `levels`.
    int first = 0;
    /// Window size (unit: px).
    glm::ivec2 size{1280, 720};
    /// Worker threads of each world (unit: count; >= 1).
    uint32_t workers = 2;
    /// Start in fullscreen.
    bool fullscreen = false;
    /// Where F12 saves screenshots.
    std::string screenshotDir = ".";
    /// Where F5 saves the level and F9 loads it back (one file per level, `<stem>.level`;
    /// created when needed).
    std::string saveDir = ".";
    /// Scripted input (`readScript`), played at the frames it names. An action whose position
    /// is off the window (its pixel outside [0, width) x [0, height) when it is played) ends
    /// the game: `finish` says "FILE:LINE: ..." and returns 2.
    std::vector<ScriptAction> script;
    /// The file `script` was read from, for those messages.
    std::string scriptPath;
    /// 0: play until the window closes. Otherwise run exactly this many frames of one step
    /// each (no real-time pacing, so a script gives the same result on any machine), print a
    /// summary line (level, time, particles per material, centre of mass, view, gravity, body
    /// positions) and exit (unit: count).
    uint32_t frames = 0;
    /// With `frames`: save the last frame, HUD included, to this PNG.
    std::string screenshot;
    /// Where to write the player's input when the game ends, as a script (`readScript`'s
    /// format, each pointer position's window pixel in a comment); empty: nothing recorded.
    /// A recorded game plays exactly one step per frame, as a scripted one, so the script
    /// replays it bit for bit; with `frames` it takes the player's input (a scripted run
    /// otherwise ignores it) and ends with the summary line.
    std::string record;
};

class Game;

/// The game as a frame callback, for hosts that own the main loop (a browser page calls
/// `frame` from its animation callback): `start`, then `frame` until it returns false, then
/// `finish`. Main thread.
class GameRunner {
public:
    /// Nothing opens until `start`.
    explicit GameRunner(const GameOptions& options);
    /// Closes what is still open.
    ~GameRunner();
    /// Not copyable: it owns the window.
    GameRunner(const GameRunner&) = delete;
    /// Not assignable either.
    GameRunner& operator=(const GameRunner&) = delete;

    /// Opens the window and the first level. False (message on stderr) when there are no
    /// levels or the window, OpenGL or the level cannot be set up; call `finish` then.
    bool start();
    /// Plays one frame: the script's actions due, the window's events, the simulation steps the
    /// real time asks for (exactly one with `frames`) and the picture. False when the game is
    /// over: the window closed, Quit chosen, or `frames` played.
    bool frame();
    /// Ends the game: a scripted run's summary line and screenshot, the recorded input. Returns
    /// the exit status: 0, 1 when it could not start or the screenshot or the recording
    /// cannot be written, 2 when a script action's position was off the window (message on
    /// stderr, no summary).
    int finish();

private:
    std::unique_ptr<Game> m_game;
};

/// Opens the window and plays until it is closed or Quit is chosen (or `frames` ran):
/// `GameRunner`'s start, frames and finish. Returns the exit status: 0, 1 when the window or
/// OpenGL cannot be set up or the screenshot cannot be written, 2 for a script action off the
/// window (message on stderr). Main thread.
int runGame(const GameOptions& options);

} // namespace fluid::demo
