// fluid-demo — headless runs.
#include "demo/headless.h"

#include "demo/banner.h"
#include "demo/frame_pacer.h"
#include "demo/hud.h"
#include "demo/imgui_bridge.h"
#include "demo/layout.h"
#include "demo/overlay.h"
#include "demo/platform.h"
#include "demo/session.h"

#include <fluid/gl/renderer.h>
#include <fluid/groups.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace fluid::demo {
namespace {

// HUD and banner as the game shows them, into the renderer's framebuffer. ImGui hides a window
// in the frame it first appears (it measures it then), so a still picture draws two frames.
void drawOverlay(ImGuiBridge& imgui, const gl::Renderer& renderer, const Session& session,
                 gl::View view) {
    const Level& level = session.level();
    HudInfo hud = hudFor(session, view);
    hud.fps = 60.0f;
    hud.speed = 1.0;
    const OverlayLayout layout = overlayLayout(renderer.size());
    for (int pass = 0; pass < 2; ++pass) {
        imgui.newFrame(renderer.size(), 1.0f / 60.0f);
        const float hudRight = drawHud(hud, layout.hud, layout.scale);
        drawLevelBanner(bannerFor(level), imgui.bannerFont(), layout, hudRight);
        if (pass == 0) {
            imgui.skipFrame();
        }
    }
    beginOverlay(renderer);
    imgui.render();
}

} // namespace

int runHeadless(const HeadlessOptions& options) {
    const bool oneFile = !options.screenshot.empty();
    if (!options.screenshotDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(options.screenshotDir, ec);
        if (ec) {
            std::fprintf(stderr, "fluid-demo: cannot create %s: %s\n",
                         options.screenshotDir.c_str(), ec.message().c_str());
            return 1;
        }
    }
    // An off-screen window for its context; a headless run never waits for the screen.
    Window window;
    WindowDef def;
    def.size = options.size;
    def.title = "fluid-demo (headless)";
    def.verticalSync = false;
    def.visible = false;
    std::unique_ptr<gl::Renderer> renderer;
    std::unique_ptr<ImGuiBridge> imgui;
    try {
        window.open(def);
        gl::loadFunctions();
        renderer = std::make_unique<gl::Renderer>(options.size);
        if (options.hud) {
            imgui = std::make_unique<ImGuiBridge>();
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fluid-demo: %s\n", e.what());
        return 1;
    }

    std::ostringstream summary;
    uint32_t totalErrors = 0;
    gl::ShapeBatch under, over;
    for (const LevelFile& file : options.levels) {
        std::unique_ptr<Session> session;
        try {
            session = std::make_unique<Session>(file, options.workers);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "fluid-demo: %s\n", e.what());
            return 1;
        }
        renderer->setMaterials(session->styles());
        const gl::Camera camera = session->camera(options.size);
        gl::RenderSettings settings;
        uint32_t levelErrors = 0;
        // At a display rate, as the game plays: fixed level frames from a frame pacer fed the
        // display's frame time, the liquid drawn between the last two at the fraction of a frame
        // the pacer holds (Interpolation::Step). Counted: the frames whose picture repeats the
        // one before while the liquid moves, drawn so and at the current positions.
        uint32_t repeated = 0, repeatedCurrent = 0, moving = 0;
        std::vector<float> drawn, lastDrawn, lastCurrent;
        FramePacerDef pacing;
        pacing.step = 1.0 / double(session->level().frameRate);
        pacing.maxFrameTime = std::max(pacing.maxFrameTime, pacing.step);
        FramePacer pacer(pacing);
        float factor = 1.0f;
        try {
            for (uint32_t frame = 1; frame <= options.frames; ++frame) {
                if (options.displayHz > 0.0f) {
                    const uint32_t steps = pacer.advance(1.0 / double(options.displayHz));
                    for (uint32_t k = 0; k < steps; ++k) {
                        session->step();
                    }
                    factor = pacer.drawFactor();
                    const World& world = session->level().world;
                    const uint32_t n = world.particleCount();
                    drawn.resize(2 * size_t(n));
                    interpolatedPositions(world, std::span(drawn).first(n),
                                          std::span(drawn).subspan(n), factor);
                    std::vector<float> current(world.positionX().begin(),
                                               world.positionX().end());
                    current.insert(current.end(), world.positionY().begin(),
                                   world.positionY().end());
                    float fastest = 0.0f;
                    for (uint32_t i = 0; i < n; ++i) {
                        fastest = std::max(fastest, std::hypot(world.velocityX()[i],
                                                               world.velocityY()[i]));
                    }
                    if (frame > 1 && fastest > 0.01f) {
                        ++moving;
                        repeated += drawn == lastDrawn ? 1 : 0;
                        repeatedCurrent += current == lastCurrent ? 1 : 0;
                    }
                    lastDrawn.swap(drawn);
                    lastCurrent.swap(current);
                } else {
                    session->step();
                }
                if (options.renderEvery > 0 && frame % options.renderEvery == 0 &&
                    frame != options.frames) {
                    session->drawShapes(camera, false, under, over, factor);
                    for (const gl::View view : options.views) {
                        settings.view = view;
                        gl::ParticleSpans spans = gl::particles(session->level().world);
                        spans.factor = factor;
                        levelErrors +=
                            renderer->render(camera, spans, under, over, settings).glErrors;
                    }
                }
            }
        } catch (const std::exception& e) {
            std::fprintf(stderr, "fluid-demo: %s: %s\n", file.stem.c_str(), e.what());
            return 1;
        }
        if (options.displayHz > 0.0f) {
            std::printf("fluid-demo: display level=%s hz=%g frames=%u moving=%u repeated=%u "
                        "repeated_current=%u\n",
                        file.stem.c_str(), double(options.displayHz), options.frames, moving,
                        repeated, repeatedCurrent);
        }
        session->drawShapes(camera, false, under, over, factor);
        gl::ParticleSpans finalSpans = gl::particles(session->level().world);
        finalSpans.factor = factor;
        for (const gl::View view : options.views) {
            settings.view = view;
            const gl::RenderStats stats = renderer->render(
                camera, finalSpans, under, over, settings);
            levelErrors += stats.glErrors;
            if (imgui) {
                drawOverlay(*imgui, *renderer, *session, view);
                levelErrors += gl::drainErrors();
            }
            const std::string path =
                oneFile ? options.screenshot
                        : (std::filesystem::path(options.screenshotDir) /
                           (file.stem + "-" + std::string(gl::viewName(view)) + ".png"))
                              .string();
            if (!savePng(*renderer, path)) {
                std::fprintf(stderr, "fluid-demo: cannot write %s\n", path.c_str());
                return 1;
            }
            char line[512];
            std::snprintf(line, sizeof line,
                          "level=%s view=%s frames=%u particles=%u size=%dx%d px_per_m=%.6g "
                          "center=%.6g,%.6g pressure_scale=%.6g gl_errors=%u file=%s",
                          file.stem.c_str(), std::string(gl::viewName(view)).c_str(),
                          options.frames, session->level().world.particleCount(), options.size.x,
                          options.size.y, double(camera.pixelsPerMetre), double(camera.center.x),
                          double(camera.center.y), double(stats.pressureScale), levelErrors,
                          path.c_str());
            std::printf("fluid-demo: %s\n", line);
            summary << line << '\n';
        }
        std::fflush(stdout);
        totalErrors += levelErrors;
    }
    if (!options.screenshotDir.empty()) {
        std::ofstream(std::filesystem::path(options.screenshotDir) / "summary.txt")
            << summary.str();
    }
    imgui.reset();
    renderer.reset();
    if (totalErrors > 0) {
        std::fprintf(stderr, "fluid-demo: %u GL error(s) while rendering\n", totalErrors);
        return 3;
    }
    return 0;
}

} // namespace fluid::demo
