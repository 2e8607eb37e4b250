// fluid-demo — the interactive game behind GameRunner: its loop (app.cpp) and its input
// (game_input.cpp).
#pragma once
#include "demo/app.h"
#include "demo/frame_pacer.h"
#include "demo/grab.h"
#include "demo/imgui_bridge.h"
#include "demo/platform.h"
#include "demo/probe.h"
#include "demo/recording.h"
#include "demo/saves.h"
#include "demo/session.h"
#include "demo/toast.h"

#include <fluid/gl/renderer.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

namespace fluid::demo {

/// The views S cycles through, in order.
inline constexpr std::array<gl::View, 3> kViews{gl::View::Metaballs, gl::View::Pressure,
                                                gl::View::Particles};

/// One game: the window, the level being played, the controls, HUD and panels. Main thread.
class Game {
public:
    /// Nothing opens until `start`.
    explicit Game(const GameOptions& options);
    /// Opens the window and the first level; false (message on stderr) when either fails.
    bool start();
    /// One frame: the script's actions due, the window's events, the simulation and the
    /// picture. False when the game is over (window closed, Quit, or the scripted frames run).
    bool frame();
    /// After the last frame: a scripted run's summary and screenshot, the recording; the exit
    /// status (`GameRunner::finish`).
    int finish();

private:
    // ---- the loop (app.cpp)
    int finishScripted();
    void createWindow(bool fullscreen);
    gl::Camera camera() const { return m_session->camera(m_renderer->size()); }
    glm::vec2 mouseWorld() const { return camera().pixelToWorld(m_mousePixel); }
    bool loadLevel(int index);
    void simulate(double realSeconds);
    void render(float realSeconds);

    // ---- the input (game_input.cpp)
    bool play(const ScriptAction& action);
    void handleEvent(const Event& input);
    void handleKey(Key key);
    void pointerPressed(const Event& event);
    void trackModifier(Key key, bool down);
    bool modifierHeld(Key left, Key right, bool tracked) const;
    void screenshot();
    void quickSave();
    void quickLoad();

    GameOptions m_options;
    int m_index = 0;
    Window m_window;
    bool m_fullscreen = false;
    std::unique_ptr<gl::Renderer> m_renderer;
    std::unique_ptr<ImGuiBridge> m_imgui;
    std::unique_ptr<Session> m_session;
    std::unique_ptr<FramePacer> m_pacer;
    gl::ShapeBatch m_under, m_over;
    Grab m_grab;
    LiquidProbe m_probe;
    QuickSaves m_saves;
    Toast m_toast;
    glm::vec2 m_mousePixel{0.0f, 0.0f};
    bool m_pointerSeen = false; // a pointer event came: m_mousePixel is the pointer's
    float m_push = 0.0f;
    bool m_shift = false, m_ctrl = false;
    size_t m_view = 0;
    float m_fps = 0.0f;
    float m_simMs = 0.0f;
    bool m_showHelp = false, m_showTuning = false, m_showMenu = false, m_quit = false;
    bool m_screenshotPending = false;
    int m_pendingLevel = -1;
    std::string m_scriptError; // a script action the window cannot play (FILE:LINE: ...)
    uint32_t m_frame = 1;      // the frame about to be played, from 1
    size_t m_next = 0;         // the next script action
    InputRecorder m_recorder;  // with `record`: the input
    std::chrono::steady_clock::time_point m_last{};  // when the last frame began
    std::chrono::steady_clock::time_point m_began{}; // when the first frame began
    double m_stepMsTotal = 0.0;                      // the simulation's time over all frames
};

} // namespace fluid::demo
