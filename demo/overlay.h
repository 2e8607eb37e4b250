// fluid-demo — the OpenGL context the game asks SFML for, and the glue between a level and
// the ImGui overlay (HUD, banner) drawn on top of the renderer's frame.
#pragma once
#include "demo/session.h"
#include "demo/ui.h"

#include <fluid/gl/renderer.h>
#include <fluid/level.h>

#include <SFML/Window/ContextSettings.hpp>
#include <SFML/Window/Window.hpp>

namespace fluid::demo {

/// OpenGL 3.3 core, 24-bit depth, 8-bit stencil, no multisampling (the renderer anti-aliases
/// its own edges).
sf::ContextSettings glContextSettings();

/// Throws `fluid::Error` naming what SFML created when `window`'s context is older than 3.3 or
/// not a core profile (SFML silently falls back when the driver refuses). Main thread.
void checkContext(const sf::Window& window);

/// Binds the renderer's framebuffer and viewport, so ImGui draws into the frame (and into
/// screenshots). Main thread, context current.
void beginOverlay(const gl::Renderer& renderer);

/// The banner of `level`: its name and goal text (or description), goal progress and time.
BannerInfo bannerFor(const Level& level);

/// The HUD fields the session knows (particles, simulation ms of the last step, sub-steps,
/// view, material, gravity); the caller fills the frame rate and the pacer's fields.
HudInfo hudFor(const Session& session, gl::View view);

/// Saves the renderer's frame as a PNG file at `path`; false if it cannot be written. Main
/// thread, context current.
bool savePng(const gl::Renderer& renderer, const std::string& path);

} // namespace fluid::demo
