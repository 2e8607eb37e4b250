// fluid-demo — the interactive game's loop: frames, simulation steps and the picture.
#include "demo/app.h"

#include "demo/banner.h"
#include "demo/game.h"
#include "demo/hud.h"
#include "demo/layout.h"
#include "demo/menus.h"
#include "demo/overlay.h"
#include "demo/summary.h"
#include "demo/tuning_panel.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fluid::demo {

Game::Game(const GameOptions& options)
    : m_options(options), m_index(options.first), m_saves(options.saveDir) {}

bool Game::start() {
    try {
        createWindow(m_options.fullscreen);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fluid-demo: %s\n", e.what());
        return false;
    }
    if (!loadLevel(m_index)) {
        return false;
    }
    m_last = std::chrono::steady_clock::now();
    m_began = m_last;
    return true;
}

bool Game::frame() {
    const bool scripted = m_options.frames > 0;
    const bool recording = !m_options.record.empty();
    if (!m_window.isOpen() || m_quit || (scripted && m_frame > m_options.frames)) {
        return false;
    }
    for (; m_next < m_options.script.size() && m_options.script[m_next].frame <= m_frame;
         ++m_next) {
        if (!play(m_options.script[m_next])) {
            return false; // a position off the window: finish says which line
        }
    }
    Event event;
    while (m_window.poll(event)) {
        // A scripted run plays its script only: the display's own pointer, focus and key
        // events (another window, a desktop) must not change the result. A recorded one
        // takes the player's input and writes it down.
        if (!scripted || recording || event.type == Event::Type::Closed) {
            handleEvent(event);
        }
    }
    if (!m_window.isOpen() || m_quit) {
        return false;
    }
    const auto now = std::chrono::steady_clock::now();
    double real = std::chrono::duration<double>(now - m_last).count();
    m_last = now;
    m_fps = m_fps <= 0.0f ? 60.0f : 0.95f * m_fps + 0.05f * float(1.0 / std::max(real, 1e-4));
    if (scripted || recording) {
        real = 1.0 / double(m_session->level().frameRate); // exactly one step a frame
    }
    simulate(real);
    render(float(real));
    ++m_frame;
    return true;
}

int Game::finish() {
    int status = 0;
    if (!m_scriptError.empty()) {
        std::fprintf(stderr, "fluid-demo: %s\n", m_scriptError.c_str());
        status = 2;
    } else if (m_options.frames > 0) {
        status = finishScripted();
    }
    if (!m_options.record.empty()) {
        // The level the game started on (the input may have changed level since).
        const int count = int(m_options.levels.size());
        const std::string& first =
            m_options.levels[size_t(((m_options.first % count) + count) % count)].stem;
        if (!m_recorder.write(m_options.record, first, m_frame - 1)) {
            status = 1;
        }
    }
    m_grab.end(nullptr);
    m_session.reset();
    m_imgui.reset();
    m_renderer.reset();
    return status;
}


int Game::finishScripted() {
    SummaryInfo info;
    info.frames = m_options.frames;
    info.view = gl::viewName(kViews[m_view]);
    info.paused = m_pacer->paused();
    const std::string probe = m_probe.summary();
    info.probe = probe;
    const std::string line = summaryLine(*m_session, info);
    std::printf("fluid-demo: %s\n", line.c_str());
    // What the frames cost here (not part of the line above, which two machines compare).
    const double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_began)
            .count();
    std::printf("fluid-demo: cost level=%s frames=%u step_ms=%.2f frame_ms=%.2f\n",
                m_session->file().stem.c_str(), m_options.frames,
                m_stepMsTotal / double(m_options.frames), wall / double(m_options.frames));
    std::fflush(stdout);
    if (!m_options.screenshot.empty()) {
        if (!savePng(*m_renderer, m_options.screenshot)) {
            std::fprintf(stderr, "fluid-demo: cannot write %s\n", m_options.screenshot.c_str());
            return 1;
        }
    }
    return 0;
}

void Game::createWindow(bool fullscreen) {
    // GL objects of the old context go first (framebuffers and vertex arrays are not
    // shared between contexts).
    m_imgui.reset();
    m_renderer.reset();
    WindowDef def;
    def.size = m_options.size;
    def.fullscreen = fullscreen;
    // A scripted run never waits for the screen.
    def.verticalSync = m_options.frames == 0;
    m_window.open(def);
    m_fullscreen = fullscreen;
    gl::loadFunctions();
    m_renderer = std::make_unique<gl::Renderer>(m_window.size());
    m_imgui = std::make_unique<ImGuiBridge>();
    if (m_session) {
        m_renderer->setMaterials(m_session->styles());
    }
}

bool Game::loadLevel(int index) {
    const int count = int(m_options.levels.size());
    index = ((index % count) + count) % count;
    try {
        m_grab.end(m_session ? m_session->level().physics.get() : nullptr);
        auto session =
            std::make_unique<Session>(m_options.levels[size_t(index)], m_options.workers);
        m_session = std::move(session);
        for (const std::string& warning : m_session->level().warnings) {
            std::fprintf(stderr, "fluid-demo: warning: %s\n", warning.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fluid-demo: %s\n", e.what());
        m_toast.show(e.what());
        return m_session != nullptr; // keep playing the old level if there is one
    }
    m_index = index;
    m_renderer->setMaterials(m_session->styles());
    FramePacerDef def;
    def.step = 1.0 / double(m_session->level().frameRate);
    def.maxFrameTime = std::max(def.maxFrameTime, def.step);
    const bool paused = m_pacer && m_pacer->paused();
    m_pacer = std::make_unique<FramePacer>(def);
    m_pacer->setPaused(paused);
    m_simMs = 0.0f;
    return true;
}

void Game::simulate(double realSeconds) {
    const uint32_t steps = m_pacer->advance(realSeconds);
    if (steps == 0) {
        return;
    }
    const float dt = 1.0f / m_session->level().frameRate;
    double total = 0.0;
    for (uint32_t i = 0; i < steps; ++i) {
        const glm::vec2 p = mouseWorld();
        m_session->setPointer(p, m_push);
        m_grab.update(p, dt);
        try {
            m_session->step();
        } catch (const std::exception& e) {
            // A world that throws mid-step is not stepped again: pause and say why.
            m_toast.show(e.what());
            m_pacer->setPaused(true);
            break;
        }
        total += m_session->lastStepMs();
    }
    m_stepMsTotal += total;
    m_pacer->reportStepCost(total / 1000.0 / steps);
    m_simMs =
        m_simMs <= 0.0f ? float(total / steps) : 0.9f * m_simMs + 0.1f * float(total / steps);
}

void Game::render(float realSeconds) {
    const gl::Camera cam = camera();
    // The pointer's ring once the pointer was seen over the window (before, it would sit at
    // the pixel (0, 0)).
    m_session->drawShapes(cam, m_pointerSeen, m_under, m_over, m_pacer->drawFactor());
    // The liquid under the cursor and the laser (L), over the liquid: 2 px wide, the normal
    // 30 px long.
    m_probe.update(m_session->level().world, mouseWorld());
    m_probe.draw(2.0f / cam.pixelsPerMetre, 30.0f / cam.pixelsPerMetre, m_over);
    gl::RenderSettings settings;
    settings.view = kViews[m_view];
    gl::ParticleSpans spans = gl::particles(m_session->level().world);
    spans.factor = m_pacer->drawFactor(); // between the last two level frames
    m_renderer->render(cam, spans, m_under, m_over, settings);
    if (m_screenshotPending) {
        // Before the overlay: the picture of the liquid, not of the HUD.
        m_screenshotPending = false;
        screenshot();
    }

    beginOverlay(*m_renderer);
    m_imgui->newFrame(m_renderer->size(), std::max(realSeconds, 1e-4f));
    const Level& level = m_session->level();
    HudInfo hud = hudFor(*m_session, kViews[m_view]);
    hud.fps = m_fps;
    hud.simMsPerFrame = m_simMs; // smoothed over frames, not the last step
    hud.paused = m_pacer->paused();
    hud.behind = m_pacer->behind();
    hud.speed = m_pacer->speed();
    hud.droppedSteps = m_pacer->droppedSteps();
    // No pointer line before the pointer was seen over the window.
    hud.cursor = m_pointerSeen ? m_probe.cursorText() : std::string_view{};
    hud.laser = m_probe.laserText();
    const OverlayLayout layout = overlayLayout(m_renderer->size());
    const float hudRight = drawHud(hud, layout.hud, layout.scale);
    BannerInfo banner = bannerFor(level);
    banner.panelOpen = m_showTuning;
    drawLevelBanner(banner, m_imgui->bannerFont(), layout, hudRight);
    if (m_showHelp) {
        drawHelp(&m_showHelp, level.name, banner.text);
    }
    if (m_showTuning) {
        drawTuningPanel(m_session->level(), &m_showTuning);
    }
    if (m_showMenu) {
        std::vector<LevelEntry> entries;
        for (const LevelFile& f : m_options.levels) {
            entries.push_back({f.stem, f.title});
        }
        const int chosen = drawLevelMenu(entries, m_index, &m_showMenu);
        if (chosen == -2) {
            m_quit = true;
        } else if (chosen >= 0) {
            m_showMenu = false;
            m_pendingLevel = chosen;
        }
    }
    m_toast.draw();
    m_imgui->render();
    m_renderer->present(m_window.size());
    m_window.display();
    if (m_pendingLevel >= 0) {
        // Switch after the frame: the menu was drawn from the old level's state.
        const int index = m_pendingLevel;
        m_pendingLevel = -1;
        loadLevel(index);
    }
}

GameRunner::GameRunner(const GameOptions& options) {
    if (!options.levels.empty()) {
        m_game = std::make_unique<Game>(options);
    }
}

GameRunner::~GameRunner() = default;

bool GameRunner::start() {
    if (m_game == nullptr) {
        std::fprintf(stderr, "fluid-demo: no levels to play\n");
        return false;
    }
    return m_game->start();
}

bool GameRunner::frame() {
    return m_game != nullptr && m_game->frame();
}

int GameRunner::finish() {
    return m_game != nullptr ? m_game->finish() : 1;
}

int runGame(const GameOptions& options) {
    GameRunner game(options);
    if (!game.start()) {
        return 1;
    }
    while (game.frame()) {
    }
    return game.finish();
}

} // namespace fluid::demo
