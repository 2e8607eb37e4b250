// fluid-demo — the platform layer: a window with an OpenGL context, its input as the game reads
// it, and PNG files. The game (app.cpp, headless.cpp, the ImGui bridge, scripts) sees only this
// header; platform_sfml.cpp implements it with SFML 2.5 on the desktop. Another platform (a
// browser page through emscripten's GLFW, issue 48) implements the same header.
#pragma once
#include <glm/vec2.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fluid::demo {

/// The keys the game, its panels and its scripts read. Values are small (below
/// `Key::Count`), so a table can be indexed by them.
enum class Key : uint16_t {
    Unknown,
    A, B, C, E, G, L, M, N, P, Q, R, S, V, X, Y, Z,
    Num1, Num2, Num3, Num4, Num5, Num6, Num7, Num8, Num9,
    Space, Period, Tab, Escape, Enter, Backspace, Delete, Insert,
    Home, End, PageUp, PageDown, Left, Right, Up, Down,
    F1, F5, F9, F11, F12,
    LShift, RShift, LControl, RControl,
    Count
};

/// Mouse buttons.
enum class MouseButton : uint8_t { Left, Right, Middle, Extra1, Extra2 };

/// One input or window event, in window pixels (origin top left, y down).
struct Event {
    /// What happened.
    enum class Type : uint8_t {
        /// The window's close button.
        Closed,
        /// The window changed size (`Window::size` has the new one).
        Resized,
        /// Keyboard focus went to another window (keys and buttons held are let go there).
        LostFocus,
        /// Keyboard focus came back.
        GainedFocus,
        /// `key` went down (no repeats while held), with the modifiers.
        KeyPressed,
        /// `key` went up, with the modifiers.
        KeyReleased,
        /// A character was typed (`unicode`).
        Text,
        /// The mouse moved to `position`.
        MouseMoved,
        /// `button` went down at `position`.
        MousePressed,
        /// `button` went up at `position`.
        MouseReleased,
        /// The wheel turned by `wheel` notches (`horizontal` for a sideways wheel).
        Wheel,
        /// The mouse left the window.
        MouseLeft,
    };
    /// See `Type`.
    Type type = Type::Closed;
    /// The key of `KeyPressed` / `KeyReleased`.
    Key key = Key::Unknown;
    /// Modifiers held with a key event.
    bool shift = false, ctrl = false, alt = false, system = false;
    /// The character of `Text` (Unicode code point).
    uint32_t unicode = 0;
    /// The button of `MousePressed` / `MouseReleased`.
    MouseButton button = MouseButton::Left;
    /// Where the mouse is for mouse events (unit: px).
    glm::ivec2 position{0, 0};
    /// Notches of `Wheel` (unit: 1; positive up or right).
    float wheel = 0.0f;
    /// `Wheel` from a sideways wheel.
    bool horizontal = false;
};

/// How to open a window.
struct WindowDef {
    /// Client area (unit: px; each >= 1); a fullscreen window takes the screen's.
    glm::ivec2 size{1280, 720};
    /// Title bar text.
    std::string title = "fluid";
    /// Fill the screen.
    bool fullscreen = false;
    /// Wait for the screen's refresh when presenting (false for scripted and headless runs,
    /// which must not depend on the display).
    bool verticalSync = true;
    /// Shown on the screen (false: an off-screen window for headless pictures).
    bool visible = true;
};

/// A window with a current OpenGL 3.3 core context (24-bit depth, 8-bit stencil, no
/// multisampling: the renderer anti-aliases its own edges). Main thread only.
class Window {
public:
    /// No window until `open`.
    Window();
    /// Closes it.
    ~Window();
    /// Not copyable: it owns the window and its context.
    Window(const Window&) = delete;
    /// Not assignable either.
    Window& operator=(const Window&) = delete;

    /// Opens the window, or opens it again with `def` (the old GL context and everything made
    /// in it go: recreate GL objects afterwards). Keys do not repeat while held. Throws
    /// `fluid::Error` naming what the driver gave when the context is not OpenGL 3.3 core
    /// (or the window cannot open).
    void open(const WindowDef& def);
    /// True from `open` until closed.
    bool isOpen() const;
    /// Closes the window.
    void close();
    /// The next pending event into `event`; false when there is none.
    bool poll(Event& event);
    /// Client area (unit: px; each >= 1).
    glm::ivec2 size() const;
    /// Shows the frame drawn into the default framebuffer.
    void display();
    /// True while `key` is held, asked of the system now (not from events).
    bool keyHeld(Key key) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// Writes `rgba` (size.x * size.y pixels, 4 bytes each, rows from the top) as a PNG file at
/// `path`; false when it cannot be written. Any thread.
bool writePng(const std::string& path, glm::ivec2 size, const std::vector<uint8_t>& rgba);

/// Keeps the files the game has just written for the player (a save, a recording) where they
/// outlive the program: on a desktop they are on disk already; a browser page copies its
/// saves to the browser's IndexedDB (`Module.fluidFilesWritten`, demo/web/index.html), so a
/// reload finds them. Main thread.
void keepFiles();

} // namespace fluid::demo
