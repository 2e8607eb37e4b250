// fluid-demo — the player's input as a script (see recording.h).
#include "demo/recording.h"

#include <cstdio>

namespace fluid::demo {

void InputRecorder::add(const Event& event, const Context& context) {
    ScriptAction action;
    action.frame = context.frame;
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
        action.ctrl = context.ctrl;
        action.shift = context.shift;
        break;
    case Event::Type::LostFocus:
        if (!context.holding) {
            return;
        }
        action.kind = ScriptAction::Kind::Release;
        break;
    default:
        return;
    }
    if (action.kind == ScriptAction::Kind::Move || action.kind == ScriptAction::Kind::Press) {
        action.position = context.camera.pixelToWorld(glm::vec2(pixel));
    } else {
        pixel = {0, 0};
    }
    m_actions.emplace_back(action, pixel);
}

bool InputRecorder::write(const std::string& path, const std::string& firstLevel,
                          uint32_t frames) const {
    std::FILE* file = std::fopen(path.c_str(), "w");
    if (file == nullptr) {
        std::fprintf(stderr, "fluid-demo: cannot write the recording %s\n", path.c_str());
        return false;
    }
    std::fprintf(file, "# fluid-demo's input from %s on, %u frames: fluid-demo --level %s "
                       "--script THIS --frames %u plays it again\n",
                 firstLevel.c_str(), frames, firstLevel.c_str(), frames);
    for (const auto& [action, pixel] : m_actions) {
        std::fprintf(file, "%s\n", scriptLine(action, &pixel).c_str());
    }
    if (std::fclose(file) != 0) {
        std::fprintf(stderr, "fluid-demo: cannot write the recording %s\n", path.c_str());
        return false;
    }
    keepFiles();
    return true;
}

} // namespace fluid::demo
