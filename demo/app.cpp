// fluid-demo — the interactive game.
#include "demo/app.h"

#include "demo/frame_pacer.h"
#include "demo/imgui_bridge.h"
#include "demo/overlay.h"
#include "demo/platform.h"
#include "demo/probe.h"
#include "demo/session.h"
#include "demo/ui.h"

#include <fluid/gl/renderer.h>
#include <fluid/internal/binary.h>

#include <box2d/box2d.h>
#include <glm/common.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace fluid::demo {
namespace {

constexpr std::array<gl::View, 3> kViews{gl::View::Metaballs, gl::View::Pressure,
                                         gl::View::Particles};

// FNV-1a (64 bit, the checksum of saves) over every particle's position and velocity, in the
// world's order, then every Box2D body's position, angle and velocities, in the level's order:
// two runs that print the same hash stepped the same bits (a desktop and a browser, say).
uint64_t stateHash(const Level& level) {
    std::vector<float> state;
    const World& world = level.world;
    for (const auto& channel :
         {world.positionX(), world.positionY(), world.velocityX(), world.velocityY()}) {
        state.insert(state.end(), channel.begin(), channel.end());
    }
    for (const auto& entry : level.bodies) {
        const b2Body* body = entry.second;
        state.insert(state.end(),
                     {body->GetPosition().x, body->GetPosition().y, body->GetAngle(),
                      body->GetLinearVelocity().x, body->GetLinearVelocity().y,
                      body->GetAngularVelocity()});
    }
    return internal::fnv1a(std::as_bytes(std::span<const float>(state)));
}

// The body under a point (dynamic or kinematic; static ground is never grabbed).
b2Body* bodyAt(b2World& world, glm::vec2 p) {
    struct Query final : b2QueryCallback {
        b2Vec2 point;
        b2Body* found = nullptr;
        bool ReportFixture(b2Fixture* fixture) override {
            b2Body* body = fixture->GetBody();
            if (body->GetType() != b2_staticBody && fixture->TestPoint(point)) {
                found = body;
                return false;
            }
            return true;
        }
    } query;
    query.point = {p.x, p.y};
    b2AABB box;
    box.lowerBound = {p.x - 1e-3f, p.y - 1e-3f};
    box.upperBound = {p.x + 1e-3f, p.y + 1e-3f};
    world.QueryAABB(&query, box);
    return query.found;
}

// A body held by the mouse (shift + drag): dynamic bodies follow a mouse joint, kinematic ones
// (the planks of "Fill the cup") get the velocity that brings the grabbed point to the cursor
// in one frame, capped, so the fluid sees them move instead of teleport.
struct Grab {
    b2Body* body = nullptr;
    b2Body* ground = nullptr;
    b2MouseJoint* joint = nullptr;
    b2Vec2 localPoint{0.0f, 0.0f};
    float spin = 0.0f; // Q / E: rad/s for kinematic bodies

    void begin(b2World& world, b2Body* target, glm::vec2 p) {
        body = target;
        localPoint = body->GetLocalPoint({p.x, p.y});
        if (body->GetType() == b2_dynamicBody) {
            b2BodyDef groundDef;
            ground = world.CreateBody(&groundDef);
            b2MouseJointDef def;
            def.bodyA = ground;
            def.bodyB = body;
            def.target = {p.x, p.y};
            def.maxForce = 300.0f * body->GetMass();
            b2LinearStiffness(def.stiffness, def.damping, 5.0f, 0.7f, def.bodyA, def.bodyB);
            joint = static_cast<b2MouseJoint*>(world.CreateJoint(&def));
        }
        body->SetAwake(true);
    }
    void update(glm::vec2 p, float dt) {
        if (body == nullptr) {
            return;
        }
        if (joint != nullptr) {
            joint->SetTarget({p.x, p.y});
            return;
        }
        const b2Vec2 at = body->GetWorldPoint(localPoint);
        b2Vec2 v{(p.x - at.x) / dt, (p.y - at.y) / dt};
        const float speed = v.Length();
        constexpr float kMaxSpeed = 3.0f; // m/s: fast enough to follow, slow enough not to splash
        if (speed > kMaxSpeed) {
            v *= kMaxSpeed / speed;
        }
        body->SetLinearVelocity(v);
        body->SetAngularVelocity(spin);
    }
    void end(b2World* world) {
        if (body != nullptr && body->GetType() == b2_kinematicBody) {
            body->SetLinearVelocity({0.0f, 0.0f});
            body->SetAngularVelocity(0.0f);
        }
        if (world != nullptr && ground != nullptr) {
            world->DestroyBody(ground); // destroys the joint too
        }
        *this = Grab{};
    }
};

} // namespace

class Game {
public:
    explicit Game(const GameOptions& options) : m_options(options), m_index(options.first) {}

    // Opens the window and the first level; false (message on stderr) when either fails.
    bool start() {
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

    // One frame: the script's actions due, the window's events, the simulation and the
    // picture. False when the game is over (window closed, Quit, or the scripted frames run).
    bool frame() {
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

    // After the last frame: a scripted run's summary and screenshot; the exit status.
    int finish() {
        int status = 0;
        if (!m_scriptError.empty()) {
            std::fprintf(stderr, "fluid-demo: %s\n", m_scriptError.c_str());
            status = 2;
        } else if (m_options.frames > 0) {
            status = finishScripted();
        }
        if (!m_options.record.empty() && !writeRecording()) {
            status = 1;
        }
        m_grab.end(nullptr);
        m_session.reset();
        m_imgui.reset();
        m_renderer.reset();
        return status;
    }

private:
    // Plays one scripted action as the events a player would cause. False, with
    // m_scriptError set, for a position off the window: a player's pointer is on it (the game
    // keeps a live one there, handleEvent), and one far off would wrap through int and drop a
    // crate or aim the pointer's force where the world cannot step.
    bool play(const ScriptAction& action) {
        const glm::vec2 pixel = camera().worldToPixel(action.position);
        const bool pointer = action.kind == ScriptAction::Kind::Move ||
                             action.kind == ScriptAction::Kind::Press;
        const glm::ivec2 size = m_renderer->size();
        // Rounded as below, the pixel is in [0, width) x [0, height); NaN is not.
        const auto on = [](float p, int n) { return p >= -0.5f && p < float(n) - 0.5f; };
        if (pointer && !(on(pixel.x, size.x) && on(pixel.y, size.y))) {
            const gl::Camera view = camera();
            char text[320];
            std::snprintf(text, sizeof text,
                          "%s:%u: '%s' at %g %g m is off the %dx%d window, which shows x in "
                          "[%.4g, %.4g] m and y in [%.4g, %.4g] m of level %s",
                          m_options.scriptPath.c_str(), action.line,
                          action.kind == ScriptAction::Kind::Move ? "move" : "press",
                          double(action.position.x), double(action.position.y), size.x, size.y,
                          double(view.worldMin().x), double(view.worldMax().x),
                          double(view.worldMin().y), double(view.worldMax().y),
                          m_session->file().stem.c_str());
            m_scriptError = text;
            return false;
        }
        const glm::ivec2 at{int(std::lround(pixel.x)), int(std::lround(pixel.y))};
        auto key = [&](Event::Type type, Key k) {
            Event e;
            e.type = type;
            e.key = k;
            handleEvent(e);
        };
        Event event;
        const MouseButton button = action.button == 0 ? MouseButton::Left : MouseButton::Right;
        switch (action.kind) {
        case ScriptAction::Kind::Key:
            key(Event::Type::KeyPressed, action.key);
            key(Event::Type::KeyReleased, action.key);
            break;
        case ScriptAction::Kind::Move:
        case ScriptAction::Kind::Press:
            event.type = Event::Type::MouseMoved;
            event.position = at;
            handleEvent(event);
            if (action.kind == ScriptAction::Kind::Move) {
                break;
            }
            if (action.shift) {
                key(Event::Type::KeyPressed, Key::LShift);
            }
            if (action.ctrl) {
                key(Event::Type::KeyPressed, Key::LControl);
            }
            event.type = Event::Type::MousePressed;
            event.button = button;
            event.position = at;
            handleEvent(event);
            break;
        case ScriptAction::Kind::Release:
            event.type = Event::Type::MouseReleased;
            event.button = button;
            event.position = {int(std::lround(m_mousePixel.x)), int(std::lround(m_mousePixel.y))};
            handleEvent(event);
            if (m_shift) {
                key(Event::Type::KeyReleased, Key::LShift);
            }
            if (m_ctrl) {
                key(Event::Type::KeyReleased, Key::LControl);
            }
            break;
        }
        return true;
    }

    // Writes down an event `handleEvent` is about to play, as the script line that plays it
    // again: keys a script can press, the pointer's moves, presses (with the modifier the
    // game reads) and releases. Losing the focus releases the buttons, as a release does.
    void recordEvent(const Event& event) {
        ScriptAction action;
        action.frame = m_frame;
        glm::ivec2 pixel = event.position;
        switch (event.type) {
        case Event::Type::KeyPressed:
            if (scriptKeyName(event.key) == nullptr) {
                return;
            }
            action.kind = ScriptAction::Kind::Key;
            action.key = event.key;
            break;
        case Event::Type::MouseMoved:
            action.kind = ScriptAction::Kind::Move;
            break;
        case Event::Type::MousePressed:
        case Event::Type::MouseReleased:
            if (event.button != MouseButton::Left && event.button != MouseButton::Right) {
                return;
            }
            action.kind = event.type == Event::Type::MousePressed ? ScriptAction::Kind::Press
                                                                  : ScriptAction::Kind::Release;
            action.button = event.button == MouseButton::Left ? 0 : 1;
            action.ctrl = modifierHeld(Key::LControl, Key::RControl, m_ctrl);
            action.shift = modifierHeld(Key::LShift, Key::RShift, m_shift);
            break;
        case Event::Type::LostFocus:
            if (m_push == 0.0f && m_grab.body == nullptr) {
                return;
            }
            action.kind = ScriptAction::Kind::Release;
            break;
        default:
            return;
        }
        if (action.kind == ScriptAction::Kind::Move || action.kind == ScriptAction::Kind::Press) {
            action.position = camera().pixelToWorld(glm::vec2(pixel));
        } else {
            pixel = {0, 0};
        }
        m_recorded.emplace_back(action, pixel);
    }

    // The recorded input, to `record`. False (message on stderr) when it cannot be written.
    bool writeRecording() const {
        std::FILE* file = std::fopen(m_options.record.c_str(), "w");
        if (file == nullptr) {
            std::fprintf(stderr, "fluid-demo: cannot write the recording %s\n",
                         m_options.record.c_str());
            return false;
        }
        // The level the game started on (the input may have changed level since).
        const int count = int(m_options.levels.size());
        const std::string& first =
            m_options.levels[size_t(((m_options.first % count) + count) % count)].stem;
        std::fprintf(file, "# fluid-demo's input from %s on, %u frames: fluid-demo --level %s "
                           "--script THIS --frames %u plays it again\n",
                     first.c_str(), m_frame - 1, first.c_str(), m_frame - 1);
        for (const auto& [action, pixel] : m_recorded) {
            std::fprintf(file, "%s\n", scriptLine(action, &pixel).c_str());
        }
        if (std::fclose(file) != 0) {
            std::fprintf(stderr, "fluid-demo: cannot write the recording %s\n",
                         m_options.record.c_str());
            return false;
        }
        keepFiles();
        return true;
    }

    // The end of a scripted run: the summary line, and the screenshot if asked.
    int finishScripted() {
        const Level& level = m_session->level();
        const World& world = level.world;
        std::string line = "level=" + m_session->file().stem;
        char buffer[160];
        std::snprintf(buffer, sizeof buffer, " frames=%u time=%.9g particles=%u", m_options.frames,
                      world.time(), world.particleCount());
        line += buffer;
        const auto x = world.positionX(), y = world.positionY();
        const auto material = world.materialIndex();
        std::vector<uint32_t> counts(world.materialCount(), 0);
        double cx = 0.0, cy = 0.0;
        for (size_t i = 0; i < x.size(); ++i) {
            ++counts[material[i]];
            cx += x[i];
            cy += y[i];
        }
        for (uint32_t m = 0; m < world.materialCount(); ++m) {
            line += " m_" + world.material(MaterialId{uint16_t(m)}).name + "=" +
                    std::to_string(counts[m]);
        }
        const double n = std::max<double>(1.0, double(x.size()));
        std::snprintf(buffer, sizeof buffer, " cx=%.4f cy=%.4f", cx / n, cy / n);
        line += buffer;
        line += " view=" + std::string(gl::viewName(kViews[m_view]));
        line += std::string(" gravity=") + (m_session->gravityOn() ? "on" : "off");
        line += " material=" + m_session->dropMaterialName();
        line += std::string(" paused=") + (m_pacer->paused() ? "1" : "0");
        line += " bodies=" + std::to_string(level.physics ? level.physics->GetBodyCount() : 0);
        constexpr const char* kGoal[] = {"none", "pending", "won", "lost"};
        std::snprintf(buffer, sizeof buffer, " goal=%s goal_value=%.4f",
                      kGoal[int(level.goalState())], level.goalValue());
        line += buffer;
        for (const auto& [name, body] : level.bodies) {
            std::snprintf(buffer, sizeof buffer, " b_%s=%.4f,%.4f", name.c_str(),
                          double(body->GetPosition().x), double(body->GetPosition().y));
            line += buffer;
        }
        line += m_probe.summary();
        std::snprintf(buffer, sizeof buffer, " hash=%016llx",
                      static_cast<unsigned long long>(stateHash(level)));
        line += buffer;
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

    void createWindow(bool fullscreen) {
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

    gl::Camera camera() const { return m_session->camera(m_renderer->size()); }

    glm::vec2 mouseWorld() const { return camera().pixelToWorld(m_mousePixel); }

    bool loadLevel(int index) {
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
            toast(e.what());
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

    void toast(std::string message) {
        m_toast = std::move(message);
        m_toastUntil = std::chrono::steady_clock::now() + std::chrono::seconds(4);
    }

    void screenshot() {
        char stamp[32];
        const std::time_t now = std::time(nullptr);
        std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
        const std::string path = (std::filesystem::path(m_options.screenshotDir) /
                                  ("fluid-" + m_session->file().stem + "-" + stamp + ".png"))
                                     .string();
        toast(savePng(*m_renderer, path) ? "Saved " + path : "Could not write " + path);
    }

    void handleKey(Key key) {
        using K = Key;
        switch (key) {
        case K::S:
            m_view = (m_view + 1) % kViews.size();
            break;
        case K::G:
            m_session->toggleGravity();
            break;
        case K::M:
            m_session->cycleDropMaterial();
            break;
        case K::Space:
            try {
                m_session->dropBlob(mouseWorld());
            } catch (const std::exception& e) {
                toast(e.what());
            }
            break;
        case K::R:
            loadLevel(m_index);
            break;
        case K::P:
            m_pacer->setPaused(!m_pacer->paused());
            break;
        case K::Period:
            m_pacer->setPaused(true);
            m_pacer->requestSingleStep();
            break;
        case K::N:
            loadLevel(m_index + 1);
            break;
        case K::B:
            loadLevel(m_index - 1);
            break;
        case K::Tab:
            m_showTuning = !m_showTuning;
            break;
        case K::F1:
            m_showHelp = !m_showHelp;
            break;
        case K::F5:
            quickSave();
            break;
        case K::F9:
            quickLoad();
            break;
        case K::F11:
            createWindow(!m_fullscreen);
            break;
        case K::F12:
            m_screenshotPending = true;
            break;
        case K::Escape:
            m_showMenu = !m_showMenu;
            break;
        case K::L:
            m_probe.toggleLaser();
            break;
        case K::Q:
            m_grab.spin = 2.0f;
            break;
        case K::E:
            m_grab.spin = -2.0f;
            break;
        default:
            if (key >= K::Num1 && key <= K::Num9) {
                const int index = int(key) - int(K::Num1);
                if (index < int(m_options.levels.size())) {
                    loadLevel(index);
                }
            }
            break;
        }
    }

    std::string quickSavePath() const {
        return (std::filesystem::path(m_options.saveDir) / (m_session->file().stem + ".level"))
            .string();
    }

    void quickSave() {
        try {
            std::filesystem::create_directories(m_options.saveDir);
            m_session->save(quickSavePath());
            keepFiles();
            toast("Saved (F9 goes back to it)");
        } catch (const std::exception& e) {
            toast(std::string("Could not save: ") + e.what());
        }
    }

    void quickLoad() {
        const std::string path = quickSavePath();
        if (!std::filesystem::exists(path)) {
            toast("No save of this level yet: F5 saves");
            return;
        }
        try {
            // A grabbed body belongs to the Box2D world about to go.
            m_grab.end(m_session->level().physics.get());
            m_session->restore(path);
            m_renderer->setMaterials(m_session->styles());
            toast("Loaded the save");
        } catch (const std::exception& e) {
            toast(std::string("Could not load: ") + e.what());
        }
    }

    void trackModifier(Key key, bool down) {
        if (key == Key::LShift || key == Key::RShift) {
            m_shift = down;
        } else if (key == Key::LControl || key == Key::RControl) {
            m_ctrl = down;
        }
    }

    // Whether a modifier is down: the game's own record of it (a script's presses) or the
    // keyboard's.
    bool modifierHeld(Key left, Key right, bool tracked) const {
        return tracked || m_window.keyHeld(left) || m_window.keyHeld(right);
    }

    void handleEvent(const Event& input) {
        // The pointer stays on the window: a drag that leaves it (the display keeps reporting
        // the pointer while a button is held) holds at its edge, so a recording's positions
        // are all ones a script may name (play).
        Event event = input;
        if (event.type == Event::Type::MouseMoved || event.type == Event::Type::MousePressed ||
            event.type == Event::Type::MouseReleased) {
            const glm::ivec2 size = m_renderer->size();
            event.position = glm::clamp(event.position, glm::ivec2(0), size - 1);
        }
        if (!m_options.record.empty()) {
            recordEvent(event);
        }
        m_imgui->processEvent(event);
        switch (event.type) {
        case Event::Type::Closed:
            m_window.close();
            break;
        case Event::Type::Resized:
            m_renderer->resize(m_window.size());
            break;
        case Event::Type::LostFocus:
            m_shift = m_ctrl = false;
            m_push = 0.0f;
            m_session->setPointer(mouseWorld(), 0.0f);
            m_grab.end(m_session->level().physics.get());
            break;
        case Event::Type::KeyPressed:
            trackModifier(event.key, true);
            if (!m_imgui->wantsKeyboard()) {
                handleKey(event.key);
            }
            break;
        case Event::Type::KeyReleased:
            trackModifier(event.key, false);
            if (event.key == Key::Q || event.key == Key::E) {
                m_grab.spin = 0.0f;
            }
            break;
        case Event::Type::MouseMoved:
            m_mousePixel = glm::vec2(event.position);
            break;
        case Event::Type::MousePressed: {
            if (m_imgui->wantsMouse()) {
                break;
            }
            m_mousePixel = glm::vec2(event.position);
            const glm::vec2 p = mouseWorld();
            const bool shift = modifierHeld(Key::LShift, Key::RShift, m_shift);
            const bool ctrl = modifierHeld(Key::LControl, Key::RControl, m_ctrl);
            b2World* physics = m_session->level().physics.get();
            if (event.button == MouseButton::Left && ctrl) {
                if (!m_session->dropCrate(p)) {
                    toast("This level has no bodies: crates drop in levels with Box2D bodies");
                }
            } else if (event.button == MouseButton::Left && shift) {
                if (physics != nullptr) {
                    if (b2Body* body = bodyAt(*physics, p)) {
                        m_grab.begin(*physics, body, p);
                    }
                }
            } else if (event.button == MouseButton::Left) {
                m_push = 1.0f;
            } else if (event.button == MouseButton::Right) {
                m_push = -1.0f;
            }
            break;
        }
        case Event::Type::MouseReleased:
            if (event.button == MouseButton::Left) {
                m_grab.end(m_session->level().physics.get());
            }
            m_push = 0.0f;
            break;
        default:
            break;
        }
    }

    void simulate(double realSeconds) {
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
                toast(e.what());
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

    void render(float realSeconds) {
        const gl::Camera cam = camera();
        m_session->drawShapes(cam, true, m_under, m_over, m_pacer->drawFactor());
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
        hud.cursor = m_probe.cursorText();
        hud.laser = m_probe.laserText();
        drawHud(hud);
        BannerInfo banner = bannerFor(level);
        banner.panelOpen = m_showTuning;
        drawLevelBanner(banner, m_imgui->bannerFont());
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
        if (!m_toast.empty() && std::chrono::steady_clock::now() < m_toastUntil) {
            drawToast(m_toast);
        }
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
    glm::vec2 m_mousePixel{0.0f, 0.0f};
    float m_push = 0.0f;
    bool m_shift = false, m_ctrl = false;
    size_t m_view = 0;
    float m_fps = 0.0f;
    float m_simMs = 0.0f;
    bool m_showHelp = false, m_showTuning = false, m_showMenu = false, m_quit = false;
    bool m_screenshotPending = false;
    int m_pendingLevel = -1;
    std::string m_toast;
    std::chrono::steady_clock::time_point m_toastUntil{};
    std::string m_scriptError; // a script action the window cannot play (FILE:LINE: ...)
    uint32_t m_frame = 1;                        // the frame about to be played, from 1
    size_t m_next = 0;                           // the next script action
    std::vector<std::pair<ScriptAction, glm::ivec2>> m_recorded; // with `record`: the input
    std::chrono::steady_clock::time_point m_last{}; // when the last frame began
    std::chrono::steady_clock::time_point m_began{}; // when the first frame began
    double m_stepMsTotal = 0.0;                      // the simulation's time over all frames
};

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
