// fluid-demo — Dear ImGui 1.86 on the platform layer's window (see imgui_bridge.h).
#include "imgui_bridge.h"

#include <fluid/error.h>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <string>

namespace fluid::demo {

namespace {
// The GLSL version ImGui's OpenGL3 backend compiles its shaders for: fluid::gl's.
#if defined(FLUID_GL_ES)
constexpr const char* kGlslVersion = "#version 300 es";
#else
constexpr const char* kGlslVersion = "#version 330 core";
#endif
constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
// Panel text and banner title sizes (unit: px).
constexpr float kFontSize = 15.0f;
constexpr float kBannerFontSize = 28.0f;

// ImGui's button index for a mouse button: 0 left, 1 right, 2 middle, 3 and 4 the extra ones.
int buttonIndex(MouseButton button) {
    return int(button);
}

// io.KeysDown is indexed by the platform layer's key values (below Key::Count).
static_assert(int(Key::Count) <= 512, "key values must fit io.KeysDown");
bool validKey(Key key) {
    return key != Key::Unknown && key < Key::Count;
}

void setModifiers(ImGuiIO& io, const Event& key) {
    io.KeyCtrl = key.ctrl;
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
    io.BackendPlatformName = "fluid_demo";

    io.KeyMap[ImGuiKey_Tab] = int(Key::Tab);
    io.KeyMap[ImGuiKey_LeftArrow] = int(Key::Left);
    io.KeyMap[ImGuiKey_RightArrow] = int(Key::Right);
    io.KeyMap[ImGuiKey_UpArrow] = int(Key::Up);
    io.KeyMap[ImGuiKey_DownArrow] = int(Key::Down);
    io.KeyMap[ImGuiKey_PageUp] = int(Key::PageUp);
    io.KeyMap[ImGuiKey_PageDown] = int(Key::PageDown);
    io.KeyMap[ImGuiKey_Home] = int(Key::Home);
    io.KeyMap[ImGuiKey_End] = int(Key::End);
    io.KeyMap[ImGuiKey_Insert] = int(Key::Insert);
    io.KeyMap[ImGuiKey_Delete] = int(Key::Delete);
    io.KeyMap[ImGuiKey_Backspace] = int(Key::Backspace);
    io.KeyMap[ImGuiKey_Space] = int(Key::Space);
    io.KeyMap[ImGuiKey_Enter] = int(Key::Enter);
    io.KeyMap[ImGuiKey_Escape] = int(Key::Escape);
    // The platform layer reports the keypad's Enter as Enter.
    io.KeyMap[ImGuiKey_KeyPadEnter] = int(Key::Enter);
    io.KeyMap[ImGuiKey_A] = int(Key::A);
    io.KeyMap[ImGuiKey_C] = int(Key::C);
    io.KeyMap[ImGuiKey_V] = int(Key::V);
    io.KeyMap[ImGuiKey_X] = int(Key::X);
    io.KeyMap[ImGuiKey_Y] = int(Key::Y);
    io.KeyMap[ImGuiKey_Z] = int(Key::Z);

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

    if (!ImGui_ImplOpenGL3_Init(kGlslVersion)) {
        ImGui::DestroyContext();
        throw Error(std::string("ImGuiBridge: ImGui_ImplOpenGL3_Init(\"") + kGlslVersion +
                    "\") failed; a GL 3.3 core (or OpenGL ES 3.0) context must be current");
    }
    m_rendererReady = true;
}

ImGuiBridge::~ImGuiBridge() {
    if (m_rendererReady) {
        ImGui_ImplOpenGL3_Shutdown();
    }
    ImGui::DestroyContext();
}

void ImGuiBridge::processEvent(const Event& event) {
    ImGuiIO& io = ImGui::GetIO();
    switch (event.type) {
    case Event::Type::KeyPressed:
    case Event::Type::KeyReleased:
        if (validKey(event.key)) {
            io.KeysDown[int(event.key)] = event.type == Event::Type::KeyPressed;
        }
        setModifiers(io, event);
        break;
    case Event::Type::Text:
        // Control characters (backspace, tab, enter, delete) arrive as key events instead.
        if (event.unicode >= 32 && event.unicode != 127) {
            io.AddInputCharacter(event.unicode);
        }
        break;
    case Event::Type::MouseMoved:
        io.MousePos = ImVec2(static_cast<float>(event.position.x),
                             static_cast<float>(event.position.y));
        break;
    case Event::Type::MousePressed:
    case Event::Type::MouseReleased: {
        io.MousePos = ImVec2(static_cast<float>(event.position.x),
                             static_cast<float>(event.position.y));
        const int index = buttonIndex(event.button);
        const bool down = event.type == Event::Type::MousePressed;
        m_mouseHeld[size_t(index)] = down;
        if (down) {
            m_mousePressed[size_t(index)] = true;
        }
        break;
    }
    case Event::Type::Wheel:
        if (event.horizontal) {
            io.MouseWheelH += event.wheel;
        } else {
            io.MouseWheel += event.wheel;
        }
        break;
    case Event::Type::MouseLeft:
        io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
        break;
    case Event::Type::LostFocus:
        // Releases never arrive for keys and buttons let go in another window.
        releaseAll();
        io.AddFocusEvent(false);
        break;
    case Event::Type::GainedFocus:
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
    m_rendererReady = ImGui_ImplOpenGL3_Init(kGlslVersion);
    if (!m_rendererReady) {
        throw Error(std::string("ImGuiBridge::reloadDeviceObjects: ImGui_ImplOpenGL3_Init(\"") +
                    kGlslVersion +
                    "\") failed; a GL 3.3 core (or OpenGL ES 3.0) context must be current");
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
