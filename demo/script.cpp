// fluid-demo — scripted input.
#include "demo/script.h"

#include <fluid/error.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace fluid::demo {
namespace {

constexpr std::pair<const char*, Key> kKeys[] = {
    {"S", Key::S},           {"G", Key::G},
    {"M", Key::M},           {"Space", Key::Space},
    {"R", Key::R},           {"P", Key::P},
    {"Period", Key::Period}, {"N", Key::N},
    {"B", Key::B},           {"Tab", Key::Tab},
    {"F1", Key::F1},         {"Escape", Key::Escape},
    {"F5", Key::F5},         {"F9", Key::F9},
    {"Q", Key::Q},           {"E", Key::E},
    {"L", Key::L},
    {"Num1", Key::Num1},     {"Num2", Key::Num2},
    {"Num3", Key::Num3},     {"Num4", Key::Num4},
    {"Num5", Key::Num5},     {"Num6", Key::Num6},
    {"Num7", Key::Num7},     {"Num8", Key::Num8},
    {"Num9", Key::Num9},
};

} // namespace

std::vector<ScriptAction> readScript(const std::string& path) {
    // A directory opens as a stream that reads nothing: it would play as an empty script.
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw Error(path + ": is a directory, not a script");
    }
    std::ifstream in(path);
    if (!in) {
        throw Error(path + ": cannot read the script");
    }
    std::vector<ScriptAction> actions;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string where = path + ":" + std::to_string(number) + ": ";
        std::istringstream words(line.substr(0, line.find('#')));
        std::string frameWord;
        if (!(words >> frameWord)) {
            continue;
        }
        ScriptAction action;
        action.line = uint32_t(number);
        try {
            size_t used = 0;
            const unsigned long frame = std::stoul(frameWord, &used);
            if (used != frameWord.size() || frame < 1 || frame > 10000000) {
                throw std::invalid_argument("frame");
            }
            action.frame = uint32_t(frame);
        } catch (const std::exception&) {
            throw Error(where + "'" + frameWord + "' is not a frame number (1 or more)");
        }
        if (!actions.empty() && action.frame < actions.back().frame) {
            throw Error(where + "frame " + frameWord + " comes before the previous line's " +
                        std::to_string(actions.back().frame));
        }
        std::string verb;
        words >> verb;
        auto readPoint = [&] {
            float x = NAN, y = NAN;
            if (!(words >> x >> y) || !std::isfinite(x) || !std::isfinite(y)) {
                throw Error(where + "'" + verb + "' needs a position X Y in metres");
            }
            action.position = {x, y};
        };
        auto readButton = [&] {
            std::string button;
            words >> button;
            if (button != "left" && button != "right") {
                throw Error(where + "'" + verb + "' needs the button 'left' or 'right', not '" +
                            button + "'");
            }
            action.button = button == "left" ? 0 : 1;
        };
        if (verb == "key") {
            std::string name;
            words >> name;
            action.kind = ScriptAction::Kind::Key;
            bool found = false;
            for (const auto& [keyName, code] : kKeys) {
                if (name == keyName) {
                    action.key = code;
                    found = true;
                }
            }
            if (!found) {
                throw Error(where + "unknown key '" + name + "'");
            }
        } else if (verb == "move") {
            action.kind = ScriptAction::Kind::Move;
            readPoint();
        } else if (verb == "press") {
            action.kind = ScriptAction::Kind::Press;
            readButton();
            readPoint();
            std::string modifier;
            if (words >> modifier) {
                if (modifier != "shift" && modifier != "ctrl") {
                    throw Error(where + "unknown modifier '" + modifier +
                                "' (expected shift or ctrl)");
                }
                action.shift = modifier == "shift";
                action.ctrl = modifier == "ctrl";
            }
        } else if (verb == "release") {
            action.kind = ScriptAction::Kind::Release;
            readButton();
        } else {
            throw Error(where + "unknown action '" + verb +
                        "' (expected key, move, press or release)");
        }
        std::string extra;
        if (words >> extra) {
            throw Error(where + "unexpected '" + extra + "' at the end of the line");
        }
        actions.push_back(action);
    }
    if (in.bad()) {
        throw Error(path + ": cannot read the script");
    }
    return actions;
}

const char* scriptKeyName(Key key) {
    for (const auto& [name, code] : kKeys) {
        if (code == key) {
            return name;
        }
    }
    return nullptr;
}

std::string scriptLine(const ScriptAction& action, const glm::ivec2* pixel) {
    const char* button = action.button == 0 ? "left" : "right";
    char buffer[160];
    switch (action.kind) {
    case ScriptAction::Kind::Key: {
        const char* name = scriptKeyName(action.key);
        std::snprintf(buffer, sizeof buffer, "%u key %s", action.frame, name ? name : "?");
        break;
    }
    case ScriptAction::Kind::Move:
        std::snprintf(buffer, sizeof buffer, "%u move %.9g %.9g", action.frame,
                      double(action.position.x), double(action.position.y));
        break;
    case ScriptAction::Kind::Press:
        std::snprintf(buffer, sizeof buffer, "%u press %s %.9g %.9g%s", action.frame, button,
                      double(action.position.x), double(action.position.y),
                      action.ctrl ? " ctrl" : action.shift ? " shift" : "");
        break;
    case ScriptAction::Kind::Release:
        std::snprintf(buffer, sizeof buffer, "%u release %s", action.frame, button);
        break;
    }
    std::string line = buffer;
    if (pixel != nullptr && action.kind != ScriptAction::Kind::Key &&
        action.kind != ScriptAction::Kind::Release) {
        line += "  # pixel " + std::to_string(pixel->x) + " " + std::to_string(pixel->y);
    }
    return line;
}

} // namespace fluid::demo
