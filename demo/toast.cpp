// fluid-demo — toasts (see toast.h).
#include "demo/toast.h"

#include "demo/ui_common.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace fluid::demo {

using namespace ui;

void drawToast(std::string_view message, float alpha) {
    if (message.empty()) {
        return;
    }
    const float a = std::isfinite(alpha) ? std::clamp(alpha, 0.0f, 1.0f) : 1.0f;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + 0.5f * viewport->WorkSize.x,
                                   viewport->WorkPos.y + viewport->WorkSize.y - 40.0f),
                            ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::PushStyleVar(ImGuiStyleVar_Alpha, a);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(16.0f, 10.0f));
    if (ImGui::Begin("##toast", nullptr, kOverlayFlags)) {
        text(message);
    }
    ImGui::End();
    ImGui::PopStyleVar(2);
}

void Toast::show(std::string message) {
    m_message = std::move(message);
    m_until = std::chrono::steady_clock::now() + std::chrono::seconds(4);
}

void Toast::draw() const {
    if (!m_message.empty() && std::chrono::steady_clock::now() < m_until) {
        drawToast(m_message);
    }
}

} // namespace fluid::demo
