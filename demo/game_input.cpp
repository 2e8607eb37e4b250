// fluid-demo — the interactive game's input: window events, keys, the mouse's push, pull,
// grab and crates, scripted actions, saves and screenshots.
#include "demo/game.h"

#include "demo/overlay.h"

#include <glm/common.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

namespace fluid::demo {

// Plays one scripted action as the events a player would cause. False, with m_scriptError
// set, for a position off the window: a player's pointer is on it (the game keeps a live one
// there, handleEvent), and one far off would wrap through int and drop a crate or aim the
// pointer's force where the world cannot step.
bool Game::play(const ScriptAction& action) {
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

void Game::handleKey(Key key) {
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
            m_toast.show(e.what());
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

void Game::screenshot() {
    const std::string path = screenshotPath(m_options.screenshotDir, m_session->file().stem);
    m_toast.show(savePng(*m_renderer, path) ? "Saved " + path : "Could not write " + path);
}

void Game::quickSave() {
    m_toast.show(m_saves.save(*m_session).message);
}

void Game::quickLoad() {
    if (m_saves.has(m_session->file().stem)) {
        // A grabbed body belongs to the Box2D world about to go.
        m_grab.end(m_session->level().physics.get());
    }
    const QuickSaves::Result result = m_saves.load(*m_session);
    if (result.ok) {
        m_renderer->setMaterials(m_session->styles());
    }
    m_toast.show(result.message);
}

void Game::trackModifier(Key key, bool down) {
    if (key == Key::LShift || key == Key::RShift) {
        m_shift = down;
    } else if (key == Key::LControl || key == Key::RControl) {
        m_ctrl = down;
    }
}

// Whether a modifier is down: the game's own record of it (a script's presses) or the
// keyboard's.
bool Game::modifierHeld(Key left, Key right, bool tracked) const {
    return tracked || m_window.keyHeld(left) || m_window.keyHeld(right);
}

void Game::handleEvent(const Event& input) {
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
        InputRecorder::Context context;
        context.frame = m_frame;
        context.camera = camera();
        context.ctrl = modifierHeld(Key::LControl, Key::RControl, m_ctrl);
        context.shift = modifierHeld(Key::LShift, Key::RShift, m_shift);
        context.holding = m_push != 0.0f || m_grab.body != nullptr;
        m_recorder.add(event, context);
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
        m_pointerSeen = true;
        break;
    case Event::Type::MousePressed:
        if (!m_imgui->wantsMouse()) {
            pointerPressed(event);
        }
        break;
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

void Game::pointerPressed(const Event& event) {
    m_mousePixel = glm::vec2(event.position);
    m_pointerSeen = true;
    const glm::vec2 p = mouseWorld();
    const bool shift = modifierHeld(Key::LShift, Key::RShift, m_shift);
    const bool ctrl = modifierHeld(Key::LControl, Key::RControl, m_ctrl);
    b2World* physics = m_session->level().physics.get();
    if (event.button == MouseButton::Left && ctrl) {
        if (!m_session->dropCrate(p)) {
            m_toast.show("This level has no bodies: crates drop in levels with Box2D bodies");
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
}

} // namespace fluid::demo
