// fluid-demo — the glue between a level and the ImGui overlay (HUD, banner) drawn on top of
// the renderer's frame.
#pragma once
#include "demo/session.h"
#include "demo/banner.h"
#include "demo/hud.h"

#include <fluid/gl/renderer.h>
#include <fluid/level.h>

namespace fluid::demo {

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
