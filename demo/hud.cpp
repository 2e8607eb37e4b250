// fluid-demo — the HUD (see hud.h).
#include "demo/hud.h"

#include "demo/ui_common.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace fluid::demo {
namespace {
using namespace ui;
using Style = HudSpan::Style;
// The smallest scale the HUD shrinks to in a box too small for it (unit: 1); below it lines
// are left out.
constexpr float kMinScale = 0.5f;

std::string format(const char* pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    return buffer;
}

ImVec4 colour(Style style) {
    switch (style) {
    case Style::Label:
        return kHint;
    case Style::Warning:
        return kAmber;
    case Style::ZeroG:
        return kCyan;
    case Style::Value:
    default:
        return ImGui::GetStyleColorVec4(ImGuiCol_Text);
    }
}
} // namespace

std::vector<std::vector<HudSpan>> hudLines(const HudInfo& info) {
    std::vector<std::vector<HudSpan>> lines;
    lines.push_back({{format("%.0f fps", double(info.fps)), Style::Value},
                     {"|", Style::Label},
                     {std::to_string(info.particles) + " particles", Style::Value}});
    lines.push_back({{format("sim %.1f ms/frame", double(info.simMsPerFrame)), Style::Value},
                     {"|", Style::Label},
                     {std::to_string(info.substeps) + " sub-steps", Style::Value}});
    std::vector<HudSpan> modes{{"view", Style::Label},
                               {std::string(info.view), Style::Value},
                               {"  material", Style::Label},
                               {std::string(info.material), Style::Value}};
    if (info.zeroG) {
        modes.push_back({"  zero-g", Style::ZeroG});
    } else {
        modes.push_back({"  gravity", Style::Label});
        modes.push_back({"on", Style::Value});
    }
    lines.push_back(std::move(modes));
    if (info.paused) {
        lines.push_back({{"PAUSED", Style::Warning}, {"P resume, . step", Style::Label}});
    }
    if (info.behind) {
        char dropped[48];
        std::snprintf(dropped, sizeof dropped, "(%llu dropped)",
                      static_cast<unsigned long long>(info.droppedSteps));
        lines.push_back(
            {{format("simulation behind: %.0f%% speed", 100.0 * std::max(info.speed, 0.0)),
              Style::Warning},
             {dropped, Style::Label}});
    }
    // The liquid under the cursor (fluid::sample) and the laser's hit (fluid::rayCast).
    if (!info.cursor.empty()) {
        lines.push_back({{"cursor", Style::Label}, {std::string(info.cursor), Style::Value}});
    }
    if (!info.laser.empty()) {
        lines.push_back({{"laser", Style::Label}, {std::string(info.laser), Style::Value}});
    }
    lines.push_back({{"F1 help   Esc levels   Tab tuning", Style::Label}});
    return lines;
}

float drawHud(const HudInfo& info, const PixelRect& box, float scale) {
    std::vector<std::vector<HudSpan>> lines = hudLines(info);
    const ImGuiStyle& style = ImGui::GetStyle();
    // The HUD's size at scale 1 (text, padding and spacing all scale together), measured in
    // the current font before the HUD's window applies its scale.
    auto lineWidth = [&](const std::vector<HudSpan>& line) {
        float width = float(line.size() - 1) * style.ItemSpacing.x;
        for (const HudSpan& span : line) {
            width += textWidth(span.text);
        }
        return width;
    };
    auto fullSize = [&] {
        float width = 0.0f;
        for (const auto& line : lines) {
            width = std::max(width, lineWidth(line));
        }
        const float n = float(lines.size());
        return ImVec2(width + 2.0f * style.WindowPadding.x,
                      n * ImGui::GetFontSize() + (n - 1.0f) * style.ItemSpacing.y +
                          2.0f * style.WindowPadding.y);
    };
    auto fit = [&] {
        const ImVec2 size = fullSize();
        return std::min({scale, box.width() / size.x, box.height() / size.y});
    };
    // A box too small for every line at the smallest scale: the hints go first, then the
    // simulation's cost, then lines from the bottom.
    while (fit() < kMinScale && lines.size() > 1) {
        const bool hints = lines.back().size() == 1 && lines.back()[0].style == Style::Label;
        lines.erase(hints ? lines.end() - 1 : lines.size() > 2 ? lines.begin() + 1 : lines.end() - 1);
    }
    const float k = std::max(fit(), kMinScale);
    const ImVec2 size = fullSize();

    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + box.min.x, viewport->WorkPos.y + box.min.y));
    ImGui::SetNextWindowBgAlpha(kOverlayBackground);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding,
                        ImVec2(k * style.WindowPadding.x, k * style.WindowPadding.y));
    ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing,
                        ImVec2(k * style.ItemSpacing.x, k * style.ItemSpacing.y));
    if (ImGui::Begin("##hud", nullptr, kOverlayFlags)) {
        ImGui::SetWindowFontScale(k);
        for (const auto& line : lines) {
            for (size_t i = 0; i < line.size(); ++i) {
                if (i > 0) {
                    ImGui::SameLine();
                }
                ImGui::PushStyleColor(ImGuiCol_Text, colour(line[i].style));
                text(line[i].text);
                ImGui::PopStyleColor();
            }
        }
    }
    ImGui::End();
    ImGui::PopStyleVar(2);
    // The right edge as laid out now (an auto-resized window takes last frame's width).
    return box.min.x + k * size.x;
}

} // namespace fluid::demo
