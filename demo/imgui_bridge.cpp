// fluid-demo — Dear ImGui 1.86 on an SFML window (see imgui_bridge.h).
#include "imgui_bridge.h"

#include <fluid/error.h>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <SFML/Window/Keyboard.hpp>
#include <SFML/Window/Mouse.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <filesystem>

namespace fluid::demo {

namespace {
constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
// Panel text and banner title sizes (unit: px).
constexpr float kFontSize = 15.0f;
constexpr float kBannerFontSize = 28.0f;

// ImGui's button index for an SFML button, or -1.
int buttonIndex(sf::Mouse::Button button) {
    switch (button) {
    case sf::Mouse::Left:
        return 0;
    case sf::Mouse::Right:
        return 1;
    case sf::Mouse::Middle:
        return 2;
    case sf::Mouse::XButton1:
        return 3;
    case sf::Mouse::XButton2:
        return 4;
    default:
        return -1;
    }
}

// io.KeysDown is indexed by SFML key codes (0 .. KeyCount-1, all below 512).
static_assert(sf::Keyboard::KeyCount <= 512, "SFML key codes must fit io.KeysDown");
bool validKey(sf::Keyboard::Key key) {
    return key >= 0 && key < sf::Keyboard::KeyCount;
}

void setModifiers(ImGuiIO& io, const sf::Event::KeyEvent& key) {
    io.KeyCtrl = key.control;
    io.KeyShift = key.shift;
    io.KeyAlt = key.alt;
    io.KeySuper = key.system;
}

void applyStyle() {
    ImGui::StyleColorsDark();
    ImGuiStyle& style = ImGui::GetStyle();
    style.WindowRounding = 6.0f;
    style.ChildRounding = 4.0f;
    style.FrameRounding = 3.0f;
    style.PopupRounding = 4.0f;
    style.GrabRounding = 3.0f;
    style.WindowBorderSize = 0.0f;
    style.WindowPadding = ImVec2(10.0f, 8.0f);
    style.ItemSpacing = ImVec2(8.0f, 5.0f);
    // Panels float over the liquid: let some of it show through.
    style.Colors[ImGuiCol_WindowBg].w = 0.88f;
}
} // namespace

ImGuiBridge::ImGuiBridge() {
    if (ImGui::GetCurrentContext() != nullptr) {
        throw Error("ImGuiBridge: a Dear ImGui context exists already; only one bridge may "
                    "exist at a time");
    }
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    // The demo keeps no window layout between runs (and must not write files in tests).
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    io.BackendPlatformName = "fluid_demo_sfml";

    io.KeyMap[ImGuiKey_Tab] = sf::Keyboard::Tab;
    io.KeyMap[ImGuiKey_LeftArrow] = sf::Keyboard::Left;
    io.KeyMap[ImGuiKey_RightArrow] = sf::Keyboard::Right;
    io.KeyMap[ImGuiKey_UpArrow] = sf::Keyboard::Up;
    io.KeyMap[ImGuiKey_DownArrow] = sf::Keyboard::Down;
    io.KeyMap[ImGuiKey_PageUp] = sf::Keyboard::PageUp;
    io.KeyMap[ImGuiKey_PageDown] = sf::Keyboard::PageDown;
    io.KeyMap[ImGuiKey_Home] = sf::Keyboard::Home;
    io.KeyMap[ImGuiKey_End] = sf::Keyboard::End;
    io.KeyMap[ImGuiKey_Insert] = sf::Keyboard::Insert;
    io.KeyMap[ImGuiKey_Delete] = sf::Keyboard::Delete;
    io.KeyMap[ImGuiKey_Backspace] = sf::Keyboard::Backspace;
    io.KeyMap[ImGuiKey_Space] = sf::Keyboard::Space;
    io.KeyMap[ImGuiKey_Enter] = sf::Keyboard::Enter;
    io.KeyMap[ImGuiKey_Escape] = sf::Keyboard::Escape;
    // SFML 2.5 reports the keypad's Enter as Enter.
    io.KeyMap[ImGuiKey_KeyPadEnter] = sf::Keyboard::Enter;
    io.KeyMap[ImGuiKey_A] = sf::Keyboard::A;
    io.KeyMap[ImGuiKey_C] = sf::Keyboard::C;
    io.KeyMap[ImGuiKey_V] = sf::Keyboard::V;
    io.KeyMap[ImGuiKey_X] = sf::Keyboard::X;
    io.KeyMap[ImGuiKey_Y] = sf::Keyboard::Y;
    io.KeyMap[ImGuiKey_Z] = sf::Keyboard::Z;

    applyStyle();

    if (std::filesystem::exists(kFontPath)) {
        // The first font added is ImGui's default.
        io.Fonts->AddFontFromFileTTF(kFontPath, kFontSize);
        m_bannerFont = io.Fonts->AddFontFromFileTTF(kFontPath, kBannerFontSize);
    }
    if (m_bannerFont == nullptr) {
        io.Fonts->Clear();
        m_bannerFont = io.Fonts->AddFontDefault();
    }

    if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
        ImGui::DestroyContext();
        throw Error("ImGuiBridge: ImGui_ImplOpenGL3_Init(\"#version 330 core\") failed; a GL "
                    "3.3 core context must be current");
    }
    m_rendererReady = true;
}

ImGuiBridge::~ImGuiBridge() {
    if (m_rendererReady) {
        ImGui_ImplOpenGL3_Shutdown();
    }
    ImGui::DestroyContext();
}

void ImGuiBridge::processEvent(const sf::Event& event) {
    ImGuiIO& io = ImGui::GetIO();
    switch (event.type) {
    case sf::Event::KeyPressed:
    case sf::Event::KeyReleased:
        if (validKey(event.key.code)) {
            io.KeysDown[event.key.code] = event.type == sf::Event::KeyPressed;
        }
        setModifiers(io, event.key);
        break;
    case sf::Event::TextEntered:
        // Control characters (backspace, tab, enter, delete) arrive as key events instead.
        if (event.text.unicode >= 32 && event.text.unicode != 127) {
            io.AddInputCharacter(event.text.unicode);
        }
        break;
    case sf::Event::MouseMoved:
        io.MousePos =
            ImVec2(static_cast<float>(event.mouseMove.x), static_cast<float>(event.mouseMove.y));
        break;
    case sf::Event::MouseButtonPressed:
    case sf::Event::MouseButtonReleased: {
        io.MousePos = ImVec2(static_cast<float>(event.mouseButton.x),
                             static_cast<float>(event.mouseButton.y));
        const int index = buttonIndex(event.mouseButton.button);
        if (index >= 0) {
            const bool down = event.type == sf::Event::MouseButtonPressed;
            m_mouseHeld[index] = down;
            if (down) {
                m_mousePressed[index] = true;
            }
        }
        break;
    }
    case sf::Event::MouseWheelScrolled:
        if (event.mouseWheelScroll.wheel == sf::Mouse::VerticalWheel) {
            io.MouseWheel += event.mouseWheelScroll.delta;
        } else {
            io.MouseWheelH += event.mouseWheelScroll.delta;
        }
        break;
    case sf::Event::MouseLeft:
        io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
        break;
    case sf::Event::LostFocus:
        // Releases never arrive for keys and buttons let go in another window.
        releaseAll();
        io.AddFocusEvent(false);
        break;
    case sf::Event::GainedFocus:
        io.AddFocusEvent(true);
        break;
    default:
        break;
    }
}

void ImGuiBridge::newFrame(glm::ivec2 windowSize, float dtSeconds) {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(std::max(windowSize.x, 0)),
                            static_cast<float>(std::max(windowSize.y, 0)));
    io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
    io.DeltaTime = std::isfinite(dtSeconds) && dtSeconds > 0.0f ? dtSeconds : 1.0f / 60.0f;
    for (std::size_t i = 0; i < m_mouseHeld.size(); ++i) {
        io.MouseDown[i] = m_mouseHeld[i] || m_mousePressed[i];
        m_mousePressed[i] = false;
    }
    if (m_rendererReady) {
        ImGui_ImplOpenGL3_NewFrame();
    }
    ImGui::NewFrame();
}

void ImGuiBridge::render() {
    ImGui::Render();
    if (m_rendererReady) {
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
}

void ImGuiBridge::skipFrame() {
    ImGui::EndFrame();
}

bool ImGuiBridge::wantsKeyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

bool ImGuiBridge::wantsMouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}

void ImGuiBridge::reloadDeviceObjects() {
    // A full shutdown and init, not Destroy/CreateDeviceObjects: the 1.86 backend keeps the
    // sizes of its old vertex and index buffers across those and then streams into the new,
    // empty ones with glBufferSubData (GL_INVALID_VALUE, nothing drawn; seen on Mesa).
    ImGui_ImplOpenGL3_Shutdown();
    m_rendererReady = ImGui_ImplOpenGL3_Init("#version 330 core");
    if (!m_rendererReady) {
        throw Error("ImGuiBridge::reloadDeviceObjects: ImGui_ImplOpenGL3_Init(\"#version 330 "
                    "core\") failed; a GL 3.3 core context must be current");
    }
    ImGui_ImplOpenGL3_CreateDeviceObjects();
}

void ImGuiBridge::releaseAll() {
    ImGuiIO& io = ImGui::GetIO();
    for (bool& key : io.KeysDown) {
        key = false;
    }
    io.KeyCtrl = io.KeyShift = io.KeyAlt = io.KeySuper = false;
    m_mouseHeld.fill(false);
    m_mousePressed.fill(false);
    for (bool& button : io.MouseDown) {
        button = false;
    }
}

} // namespace fluid::demo
