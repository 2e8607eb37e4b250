// fluid-demo — the platform layer with GLFW 3 and an OpenGL ES 3.0 context (see platform.h):
// the browser page's, through emscripten's GLFW (WebGL2 on a canvas). Written against GLFW 3's
// API only; no native build uses it yet.
#include "demo/platform.h"

#include <fluid/error.h>

#define GLFW_INCLUDE_ES3
#include <GLFW/glfw3.h>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#endif

#include <algorithm>
#include <deque>
#include <utility>

namespace fluid::demo {

namespace {

// The GLFW key of each platform key.
constexpr std::pair<Key, int> kKeys[] = {
    {Key::A, GLFW_KEY_A},           {Key::B, GLFW_KEY_B},
    {Key::C, GLFW_KEY_C},           {Key::E, GLFW_KEY_E},
    {Key::G, GLFW_KEY_G},           {Key::M, GLFW_KEY_M},
    {Key::N, GLFW_KEY_N},           {Key::P, GLFW_KEY_P},
    {Key::Q, GLFW_KEY_Q},           {Key::R, GLFW_KEY_R},
    {Key::S, GLFW_KEY_S},           {Key::V, GLFW_KEY_V},
    {Key::L, GLFW_KEY_L},
    {Key::X, GLFW_KEY_X},           {Key::Y, GLFW_KEY_Y},
    {Key::Z, GLFW_KEY_Z},           {Key::Num1, GLFW_KEY_1},
    {Key::Num2, GLFW_KEY_2},        {Key::Num3, GLFW_KEY_3},
    {Key::Num4, GLFW_KEY_4},        {Key::Num5, GLFW_KEY_5},
    {Key::Num6, GLFW_KEY_6},        {Key::Num7, GLFW_KEY_7},
    {Key::Num8, GLFW_KEY_8},        {Key::Num9, GLFW_KEY_9},
    {Key::Space, GLFW_KEY_SPACE},   {Key::Period, GLFW_KEY_PERIOD},
    {Key::Tab, GLFW_KEY_TAB},       {Key::Escape, GLFW_KEY_ESCAPE},
    {Key::Enter, GLFW_KEY_ENTER},   {Key::Backspace, GLFW_KEY_BACKSPACE},
    {Key::Delete, GLFW_KEY_DELETE}, {Key::Insert, GLFW_KEY_INSERT},
    {Key::Home, GLFW_KEY_HOME},     {Key::End, GLFW_KEY_END},
    {Key::PageUp, GLFW_KEY_PAGE_UP}, {Key::PageDown, GLFW_KEY_PAGE_DOWN},
    {Key::Left, GLFW_KEY_LEFT},     {Key::Right, GLFW_KEY_RIGHT},
    {Key::Up, GLFW_KEY_UP},         {Key::Down, GLFW_KEY_DOWN},
    {Key::F1, GLFW_KEY_F1},         {Key::F5, GLFW_KEY_F5},
    {Key::F9, GLFW_KEY_F9},         {Key::F11, GLFW_KEY_F11},
    {Key::F12, GLFW_KEY_F12},       {Key::LShift, GLFW_KEY_LEFT_SHIFT},
    {Key::RShift, GLFW_KEY_RIGHT_SHIFT}, {Key::LControl, GLFW_KEY_LEFT_CONTROL},
    {Key::RControl, GLFW_KEY_RIGHT_CONTROL},
};

Key fromGlfw(int key) {
    for (const auto& [ours, theirs] : kKeys) {
        if (theirs == key) {
            return ours;
        }
    }
    return Key::Unknown;
}

int toGlfw(Key key) {
    for (const auto& [ours, theirs] : kKeys) {
        if (ours == key) {
            return theirs;
        }
    }
    return GLFW_KEY_UNKNOWN;
}

MouseButton fromGlfwButton(int button) {
    switch (button) {
    case GLFW_MOUSE_BUTTON_RIGHT:
        return MouseButton::Right;
    case GLFW_MOUSE_BUTTON_MIDDLE:
        return MouseButton::Middle;
    case GLFW_MOUSE_BUTTON_4:
        return MouseButton::Extra1;
    case GLFW_MOUSE_BUTTON_5:
        return MouseButton::Extra2;
    default:
        return MouseButton::Left;
    }
}

} // namespace

struct Window::Impl {
    GLFWwindow* window = nullptr;
    std::deque<Event> events;
    glm::ivec2 cursor{0, 0};

    static Impl& of(GLFWwindow* w) { return *static_cast<Impl*>(glfwGetWindowUserPointer(w)); }

    void push(Event e) { events.push_back(e); }

    void destroy() {
        if (window != nullptr) {
            glfwDestroyWindow(window);
            window = nullptr;
        }
        events.clear();
    }
};

Window::Window() : m_impl(std::make_unique<Impl>()) {}

Window::~Window() {
    m_impl->destroy();
}

void Window::open(const WindowDef& def) {
    m_impl->destroy();
    if (glfwInit() != GLFW_TRUE) {
        throw Error("cannot start GLFW (no display?)");
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_STENCIL_BITS, 8);
    glfwWindowHint(GLFW_SAMPLES, 0);
    glfwWindowHint(GLFW_VISIBLE, def.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWmonitor* monitor = def.fullscreen ? glfwGetPrimaryMonitor() : nullptr;
    glm::ivec2 size = def.size;
    if (monitor != nullptr) {
        if (const GLFWvidmode* mode = glfwGetVideoMode(monitor)) {
            size = {mode->width, mode->height};
        }
    }
    GLFWwindow* w = glfwCreateWindow(size.x, size.y, def.title.c_str(), monitor, nullptr);
    if (w == nullptr) {
        throw Error("needs an OpenGL ES 3.0 context (WebGL2 in a browser), which GLFW could "
                    "not create");
    }
    m_impl->window = w;
    glfwSetWindowUserPointer(w, m_impl.get());
    glfwMakeContextCurrent(w);
    glfwSwapInterval(def.verticalSync ? 1 : 0);
    glfwSetWindowCloseCallback(w, [](GLFWwindow* win) {
        Event e;
        e.type = Event::Type::Closed;
        Impl::of(win).push(e);
    });
    glfwSetFramebufferSizeCallback(w, [](GLFWwindow* win, int, int) {
        Event e;
        e.type = Event::Type::Resized;
        Impl::of(win).push(e);
    });
    glfwSetWindowFocusCallback(w, [](GLFWwindow* win, int focused) {
        Event e;
        e.type = focused ? Event::Type::GainedFocus : Event::Type::LostFocus;
        Impl::of(win).push(e);
    });
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
        if (action == GLFW_REPEAT) {
            return; // keys do not repeat while held, as on the desktop
        }
        Event e;
        e.type = action == GLFW_PRESS ? Event::Type::KeyPressed : Event::Type::KeyReleased;
        e.key = fromGlfw(key);
        e.shift = (mods & GLFW_MOD_SHIFT) != 0;
        e.ctrl = (mods & GLFW_MOD_CONTROL) != 0;
        e.alt = (mods & GLFW_MOD_ALT) != 0;
        e.system = (mods & GLFW_MOD_SUPER) != 0;
        Impl::of(win).push(e);
    });
    glfwSetCharCallback(w, [](GLFWwindow* win, unsigned int codepoint) {
        Event e;
        e.type = Event::Type::Text;
        e.unicode = codepoint;
        Impl::of(win).push(e);
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
        Impl& impl = Impl::of(win);
        impl.cursor = {int(x), int(y)};
        Event e;
        e.type = Event::Type::MouseMoved;
        e.position = impl.cursor;
        impl.push(e);
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
        Impl& impl = Impl::of(win);
        Event e;
        e.type = action == GLFW_PRESS ? Event::Type::MousePressed : Event::Type::MouseReleased;
        e.button = fromGlfwButton(button);
        // Where the button went down, even without a move before it (a finger's first touch).
        double x = 0.0, y = 0.0;
        glfwGetCursorPos(win, &x, &y);
        impl.cursor = {int(x), int(y)};
        e.position = impl.cursor;
        impl.push(e);
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double dx, double dy) {
        Impl& impl = Impl::of(win);
        Event e;
        e.type = Event::Type::Wheel;
        e.position = impl.cursor;
        e.horizontal = dx != 0.0 && dy == 0.0;
        e.wheel = float(e.horizontal ? dx : dy);
        impl.push(e);
    });
    glfwSetCursorEnterCallback(w, [](GLFWwindow* win, int entered) {
        if (!entered) {
            Event e;
            e.type = Event::Type::MouseLeft;
            Impl::of(win).push(e);
        }
    });
}

bool Window::isOpen() const {
    return m_impl->window != nullptr;
}

void Window::close() {
    m_impl->destroy();
}

bool Window::poll(Event& event) {
    if (m_impl->window == nullptr) {
        return false;
    }
    if (m_impl->events.empty()) {
        glfwPollEvents();
    }
    if (m_impl->events.empty()) {
        return false;
    }
    event = m_impl->events.front();
    m_impl->events.pop_front();
    return true;
}

glm::ivec2 Window::size() const {
    int w = 1, h = 1;
    if (m_impl->window != nullptr) {
        glfwGetFramebufferSize(m_impl->window, &w, &h);
    }
    return {std::max(1, w), std::max(1, h)};
}

void Window::display() {
    if (m_impl->window != nullptr) {
        glfwSwapBuffers(m_impl->window);
    }
}

bool Window::keyHeld(Key key) const {
    const int code = toGlfw(key);
    return m_impl->window != nullptr && code != GLFW_KEY_UNKNOWN &&
           glfwGetKey(m_impl->window, code) == GLFW_PRESS;
}

#ifdef __EMSCRIPTEN__
namespace {
// The page's hook (demo/web/index.html), when it has one.
EM_JS(void, callFilesWritten, (), {
    if (Module.fluidFilesWritten) {
        Module.fluidFilesWritten();
    }
});
} // namespace

void keepFiles() {
    callFilesWritten();
}
#else
void keepFiles() {}
#endif

} // namespace fluid::demo
