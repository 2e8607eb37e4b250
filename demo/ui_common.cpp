// fluid-demo — the overlays' text helpers (see ui_common.h).
#include "demo/ui_common.h"

namespace fluid::demo::ui {

void text(std::string_view s) {
    if (s.empty()) {
        ImGui::TextUnformatted("");
        return;
    }
    ImGui::TextUnformatted(s.data(), s.data() + s.size());
}

float textWidth(std::string_view s) {
    return s.empty() ? 0.0f : ImGui::CalcTextSize(s.data(), s.data() + s.size()).x;
}

void centredText(std::string_view s) {
    const float width = textWidth(s);
    const float avail = ImGui::GetContentRegionAvail().x;
    if (width < avail) {
        ImGui::SetCursorPosX(ImGui::GetCursorPosX() + 0.5f * (avail - width));
    }
    text(s);
}

BigFont::BigFont(ImFont* big, float scale) {
    if (big != nullptr && big->FontSize >= 20.0f) {
        ImGui::PushFont(big);
        m_pushed = true;
        if (scale != 1.0f) {
            ImGui::SetWindowFontScale(scale);
            m_scaled = true;
        }
    } else {
        ImGui::SetWindowFontScale(scale * kBannerSize / ImGui::GetFontSize());
        m_scaled = true;
    }
}

BigFont::~BigFont() {
    if (m_scaled) {
        ImGui::SetWindowFontScale(1.0f);
    }
    if (m_pushed) {
        ImGui::PopFont();
    }
}

} // namespace fluid::demo::ui
