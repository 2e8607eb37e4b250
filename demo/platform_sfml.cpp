// fluid-demo — the platform layer with SFML 2.5 (see platform.h).
#include "demo/platform.h"

#include <fluid/error.h>

#include <SFML/Graphics/Image.hpp>
#include <SFML/System/Err.hpp>
#include <SFML/Window.hpp>

#include <sstream>
#include <utility>

namespace fluid::demo {

namespace {

// The SFML key of each platform key.
constexpr std::pair<Key, sf::Keyboard::Key> kKeys[] = {
    {Key::A, sf::Keyboard::A},           {Key::B, sf::Keyboard::B},
    {Key::C, sf::Keyboard::C},           {Key::E, sf::Keyboard::E},
    {Key::G, sf::Keyboard::G},           {Key::M, sf::Keyboard::M},
    {Key::N, sf::Keyboard::N},           {Key::P, sf::Keyboard::P},
    {Key::Q, sf::Keyboard::Q},           {Key::R, sf::Keyboard::R},
    {Key::S, sf::Keyboard::S},           {Key::V, sf::Keyboard::V},
    {Key::L, sf::Keyboard::L},
    {Key::X, sf::Keyboard::X},           {Key::Y, sf::Keyboard::Y},
    {Key::Z, sf::Keyboard::Z},           {Key::Num1, sf::Keyboard::Num1},
    {Key::Num2, sf::Keyboard::Num2},     {Key::Num3, sf::Keyboard::Num3},
    {Key::Num4, sf::Keyboard::Num4},     {Key::Num5, sf::Keyboard::Num5},
    {Key::Num6, sf::Keyboard::Num6},     {Key::Num7, sf::Keyboard::Num7},
    {Key::Num8, sf::Keyboard::Num8},     {Key::Num9, sf::Keyboard::Num9},
    {Key::Space, sf::Keyboard::Space},   {Key::Period, sf::Keyboard::Period},
    {Key::Tab, sf::Keyboard::Tab},       {Key::Escape, sf::Keyboard::Escape},
    {Key::Enter, sf::Keyboard::Enter},   {Key::Backspace, sf::Keyboard::Backspace},
    {Key::Delete, sf::Keyboard::Delete}, {Key::Insert, sf::Keyboard::Insert},
    {Key::Home, sf::Keyboard::Home},     {Key::End, sf::Keyboard::End},
    {Key::PageUp, sf::Keyboard::PageUp}, {Key::PageDown, sf::Keyboard::PageDown},
    {Key::Left, sf::Keyboard::Left},     {Key::Right, sf::Keyboard::Right},
    {Key::Up, sf::Keyboard::Up},         {Key::Down, sf::Keyboard::Down},
    {Key::F1, sf::Keyboard::F1},         {Key::F5, sf::Keyboard::F5},
    {Key::F9, sf::Keyboard::F9},         {Key::F11, sf::Keyboard::F11},
    {Key::F12, sf::Keyboard::F12},       {Key::LShift, sf::Keyboard::LShift},
    {Key::RShift, sf::Keyboard::RShift}, {Key::LControl, sf::Keyboard::LControl},
    {Key::RControl, sf::Keyboard::RControl},
};

Key fromSfml(sf::Keyboard::Key key) {
    for (const auto& [ours, theirs] : kKeys) {
        if (theirs == key) {
            return ours;
        }
    }
    return Key::Unknown;
}

sf::Keyboard::Key toSfml(Key key) {
    for (const auto& [ours, theirs] : kKeys) {
        if (ours == key) {
            return theirs;
        }
    }
    return sf::Keyboard::Unknown;
}

MouseButton fromSfml(sf::Mouse::Button button) {
    switch (button) {
    case sf::Mouse::Right:
        return MouseButton::Right;
    case sf::Mouse::Middle:
        return MouseButton::Middle;
    case sf::Mouse::XButton1:
        return MouseButton::Extra1;
    case sf::Mouse::XButton2:
        return MouseButton::Extra2;
    default:
        return MouseButton::Left;
    }
}

// OpenGL 3.3 core, 24-bit depth, 8-bit stencil, no multisampling.
sf::ContextSettings contextSettings() {
    return sf::ContextSettings(24, 8, 0, 3, 3, sf::ContextSettings::Core);
}

// Throws naming what SFML created when the context is older than 3.3 or not a core profile
// (SFML silently falls back when the driver refuses).
void checkContext(const sf::Window& window) {
    const sf::ContextSettings got = window.getSettings();
    const bool core = (got.attributeFlags & sf::ContextSettings::Core) != 0;
    if (got.majorVersion * 10 + got.minorVersion < 33 || !core) {
        throw Error("needs an OpenGL 3.3 core context, but the driver gave OpenGL " +
                    std::to_string(got.majorVersion) + "." + std::to_string(got.minorVersion) +
                    (core ? " core" : " compatibility") +
                    " (software rendering: Mesa's llvmpipe provides 3.3 core, e.g. under Xvfb)");
    }
}

} // namespace

struct Window::Impl {
    sf::Window window;
};

Window::Window() : m_impl(std::make_unique<Impl>()) {}

Window::~Window() = default;

void Window::open(const WindowDef& def) {
    sf::Window& window = m_impl->window;
    // SFML turns vertical sync off on every new window and says on sf::err() when the display
    // cannot (a virtual one); a window that does not ask for it drops that line, and anything
    // else SFML says is passed on.
    std::stringstream sfmlSays;
    std::streambuf* const sfmlErr = !def.verticalSync ? sf::err().rdbuf(sfmlSays.rdbuf()) : nullptr;
    if (def.fullscreen) {
        window.create(sf::VideoMode::getDesktopMode(), def.title, sf::Style::Fullscreen,
                      contextSettings());
    } else {
        window.create(sf::VideoMode(unsigned(def.size.x), unsigned(def.size.y)), def.title,
                      def.visible ? sf::Style::Default : sf::Style::Titlebar, contextSettings());
        window.setPosition({0, 0}); // without a window manager SFML places it off-screen
    }
    if (def.verticalSync) {
        window.setVerticalSyncEnabled(true);
    } else {
        sf::err().rdbuf(sfmlErr);
        for (std::string line; std::getline(sfmlSays, line);) {
            if (line != "Setting vertical sync not supported") {
                sf::err() << line << '\n';
            }
        }
    }
    if (!def.visible) {
        window.setVisible(false);
    }
    window.setKeyRepeatEnabled(false);
    checkContext(window);
}

bool Window::isOpen() const {
    return m_impl->window.isOpen();
}

void Window::close() {
    m_impl->window.close();
}

bool Window::poll(Event& event) {
    sf::Event e;
    while (m_impl->window.pollEvent(e)) {
        event = Event{};
        switch (e.type) {
        case sf::Event::Closed:
            event.type = Event::Type::Closed;
            return true;
        case sf::Event::Resized:
            event.type = Event::Type::Resized;
            return true;
        case sf::Event::LostFocus:
            event.type = Event::Type::LostFocus;
            return true;
        case sf::Event::GainedFocus:
            event.type = Event::Type::GainedFocus;
            return true;
        case sf::Event::KeyPressed:
        case sf::Event::KeyReleased:
            event.type = e.type == sf::Event::KeyPressed ? Event::Type::KeyPressed
                                                         : Event::Type::KeyReleased;
            event.key = fromSfml(e.key.code);
            event.shift = e.key.shift;
            event.ctrl = e.key.control;
            event.alt = e.key.alt;
            event.system = e.key.system;
            return true;
        case sf::Event::TextEntered:
            event.type = Event::Type::Text;
            event.unicode = e.text.unicode;
            return true;
        case sf::Event::MouseMoved:
            event.type = Event::Type::MouseMoved;
            event.position = {e.mouseMove.x, e.mouseMove.y};
            return true;
        case sf::Event::MouseButtonPressed:
        case sf::Event::MouseButtonReleased:
            event.type = e.type == sf::Event::MouseButtonPressed ? Event::Type::MousePressed
                                                                 : Event::Type::MouseReleased;
            event.button = fromSfml(e.mouseButton.button);
            event.position = {e.mouseButton.x, e.mouseButton.y};
            return true;
        case sf::Event::MouseWheelScrolled:
            event.type = Event::Type::Wheel;
            event.wheel = e.mouseWheelScroll.delta;
            event.horizontal = e.mouseWheelScroll.wheel != sf::Mouse::VerticalWheel;
            event.position = {e.mouseWheelScroll.x, e.mouseWheelScroll.y};
            return true;
        case sf::Event::MouseLeft:
            event.type = Event::Type::MouseLeft;
            return true;
        default:
            break; // not one the game reads: the next
        }
    }
    return false;
}

glm::ivec2 Window::size() const {
    const sf::Vector2u s = m_impl->window.getSize();
    return {std::max(1u, s.x), std::max(1u, s.y)};
}

void Window::display() {
    m_impl->window.display();
}

bool Window::keyHeld(Key key) const {
    const sf::Keyboard::Key code = toSfml(key);
    return code != sf::Keyboard::Unknown && sf::Keyboard::isKeyPressed(code);
}

bool writePng(const std::string& path, glm::ivec2 size, const std::vector<uint8_t>& rgba) {
    if (size.x <= 0 || size.y <= 0 || rgba.size() < size_t(size.x) * size_t(size.y) * 4) {
        return false;
    }
    sf::Image image;
    image.create(unsigned(size.x), unsigned(size.y), rgba.data());
    return image.saveToFile(path);
}

void keepFiles() {}

} // namespace fluid::demo
