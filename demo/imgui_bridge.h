// fluid-demo — Dear ImGui 1.86 on the platform layer's window (platform.h): input by hand (the
// layer's events; Debian's ImGui predates the 1.87 event API), drawing with ImGui's OpenGL3
// backend.
#pragma once

#include "demo/platform.h"

#include <glm/vec2.hpp>

#include <array>

struct ImFont;

namespace fluid::demo {

/// Owns the Dear ImGui context and its OpenGL 3 renderer, and feeds it the window's input.
///
/// Use per frame: `processEvent` for every window event, then `newFrame`, the `ImGui::` calls
/// (see ui.h), then `render` before `display()`. Ask `wantsKeyboard` / `wantsMouse` before
/// giving an event to the game: they are true while a panel has focus or the mouse is over one
/// (as of the last frame, ImGui's usual one-frame lag).
///
/// Thread rule: the thread that owns the GL context. Dear ImGui keeps one current context per
/// process, so only one bridge may exist at a time (the constructor throws otherwise). Create
/// it after the window (a GL 3.3 context must be current) and destroy it before the window.
class ImGuiBridge {
public:
    /// Creates the ImGui context (no imgui.ini: `IniFilename` = nullptr), maps the keys, loads
    /// the fonts (DejaVu Sans 15 px for panels and 28 px for banners when
    /// /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf exists; ImGui's built-in font
    /// otherwise) and initialises the OpenGL3 renderer with "#version 330 core". Throws
    /// `fluid::Error` when another bridge exists or the renderer cannot start.
    ImGuiBridge();
    /// Shuts the renderer down and destroys the context (GL context still current).
    ~ImGuiBridge();
    /// Not copyable: it owns the process's ImGui context.
    ImGuiBridge(const ImGuiBridge&) = delete;
    /// Not assignable either.
    ImGuiBridge& operator=(const ImGuiBridge&) = delete;

    /// Feeds one window event: keys (with Ctrl, Shift, Alt, Super), text (characters >= 32 but
    /// not 127), mouse position, buttons and wheels. Losing focus releases every key and
    /// button; the mouse leaving the window hides its position from ImGui.
    void processEvent(const Event& event);
    /// Starts an ImGui frame for a window of `windowSize` pixels (unit: px; each >= 0) after
    /// `dtSeconds` of real time (unit: s; a value <= 0 or non-finite reads as 1/60, ImGui needs
    /// a positive time step). A button pressed and released since the last frame still
    /// counts as one click.
    void newFrame(glm::ivec2 windowSize, float dtSeconds);
    /// Ends the frame and draws it into the current framebuffer (viewport set by ImGui; the
    /// caller's blend, scissor and depth state is changed).
    void render();
    /// Ends the frame without drawing it. ImGui measures a window during the frame it first
    /// appears in and shows it from the next one, so a one-shot picture (a headless
    /// screenshot) runs newFrame, the panels and skipFrame once, then newFrame, the same
    /// panels and render.
    void skipFrame();
    /// True when ImGui uses the keyboard (a text field or panel with focus).
    bool wantsKeyboard() const;
    /// True when ImGui uses the mouse (the cursor over a panel, or dragging a widget).
    bool wantsMouse() const;
    /// Restarts the OpenGL3 renderer (shader, buffers, font texture) after the GL context was
    /// recreated (fullscreen toggle: `Window::open`), the new context current. The desktop's
    /// SFML shares objects between its contexts, so the old names are deleted, not leaked. Throws
    /// `fluid::Error` if the renderer cannot start again; the bridge then draws nothing until
    /// a later call succeeds.
    void reloadDeviceObjects();
    /// Font for banners (about 28 px): DejaVu Sans when found, else ImGui's default font; in
    /// that case its `FontSize` is 13 and ui_common.cpp scales it up (BigFont). Valid for the bridge's life.
    ImFont* bannerFont() const { return m_bannerFont; }

private:
    void releaseAll();

    ImFont* m_bannerFont = nullptr;
    bool m_rendererReady = false; // ImGui_ImplOpenGL3_Init succeeded (and no Shutdown since)
    // Mouse buttons held now, and pressed since the last newFrame (ImGui 1.86 samples the
    // button state once per frame, so a quick click would otherwise be missed).
    std::array<bool, 5> m_mouseHeld{};
    std::array<bool, 5> m_mousePressed{};
};

} // namespace fluid::demo
