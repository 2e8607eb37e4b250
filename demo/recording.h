// fluid-demo — writing the player's input down as a script (--record) that replays it.
#pragma once
#include "demo/platform.h"
#include "demo/script.h"

#include <fluid/gl/camera.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace fluid::demo {

/// The input of a game, as script actions with the window pixel each was made at. Main thread.
class InputRecorder {
public:
    /// What the game knows of an event besides the event itself.
    struct Context {
        /// The frame about to be played (unit: count, from 1).
        uint32_t frame = 1;
        /// The camera the pointer's pixel maps to metres with.
        gl::Camera camera;
        /// Whether Ctrl / Shift are held (the game's record or the keyboard's).
        bool ctrl = false;
        /// See `ctrl`.
        bool shift = false;
        /// Whether a button pushes, pulls or grabs: losing the focus then releases it.
        bool holding = false;
    };

    /// Writes down an event the game is about to play, as the script line that plays it
    /// again: keys a script can press, the pointer's moves, presses (with the modifier the
    /// game reads) and releases. Losing the focus while `holding` is a release. Other events
    /// are not recorded.
    void add(const Event& event, const Context& context);

    /// Writes the recording to `path`: a comment naming `firstLevel` and the `frames` played,
    /// then one line per action (`scriptLine`, the pixel in a comment). False (message on
    /// stderr) when it cannot be written.
    bool write(const std::string& path, const std::string& firstLevel, uint32_t frames) const;

private:
    std::vector<std::pair<ScriptAction, glm::ivec2>> m_actions;
};

} // namespace fluid::demo
