// fluid-demo — the HUD (see hud.h).
#include "demo/hud.h"

#include "demo/ui_common.h"

#include <imgui.h>

#include <algorithm>

namespace fluid::demo {
namespace {
using namespace ui;
// Where the HUD ends, margin included, before it was first measured (unit: px).
constexpr float kHudRight = 260.0f;
// Right edge of the HUD as last drawn, margin included (unit: px); the banner keeps clear of
// it. Demo UI state, one HUD per process like ImGui's own context.
float g_hudRight = kHudRight;
} // namespace

float hudRight() {
    return g_hudRight;
}

void drawHud(const HudInfo& info) {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + kEdge, viewport->WorkPos.y + kEdge));
    ImGui::SetNextWindowBgAlpha(kOverlayBackground);
    const HintColour hints;
    if (ImGui::Begin("##hud", nullptr, kOverlayFlags)) {
        ImGui::Text("%.0f fps", static_cast<double>(info.fps));
        ImGui::SameLine();
        ImGui::TextDisabled("|");
        ImGui::SameLine();
        ImGui::Text("%u particles", info.particles);
        ImGui::Text("sim %.1f ms/frame", static_cast<double>(info.simMsPerFrame));
        ImGui::SameLine();
        ImGui::TextDisabled("|");
        ImGui::SameLine();
        ImGui::Text("%u sub-steps", info.substeps);
        ImGui::TextDisabled("view");
        ImGui::SameLine();
        text(info.view);
        ImGui::SameLine();
        ImGui::TextDisabled("  material");
        ImGui::SameLine();
        text(info.material);
        if (info.zeroG) {
            ImGui::TextColored(kCyan, "zero-g");
        } else {
            ImGui::TextDisabled("gravity");
            ImGui::SameLine();
            text("on");
        }
        if (info.paused) {
            ImGui::TextColored(kAmber, "PAUSED");
            ImGui::SameLine();
            ImGui::TextDisabled("P resume, . step");
        }
        if (info.behind) {
            ImGui::TextColored(kAmber, "simulation behind: %.0f%% speed",
                               100.0 * std::max(info.speed, 0.0));
            ImGui::SameLine();
            ImGui::TextDisabled("(%llu dropped)",
                                static_cast<unsigned long long>(info.droppedSteps));
        }
        // The liquid under the cursor (fluid::sample) and the laser's hit (fluid::rayCast).
        if (!info.cursor.empty()) {
            ImGui::TextDisabled("cursor");
            ImGui::SameLine();
            text(info.cursor);
        }
        if (!info.laser.empty()) {
            ImGui::TextDisabled("laser");
            ImGui::SameLine();
            text(info.laser);
        }
        ImGui::TextDisabled("F1 help   Esc levels   Tab tuning");
        // Auto-resized: the size is the one measured in an earlier frame.
        g_hudRight =
            ImGui::GetWindowPos().x - viewport->WorkPos.x + ImGui::GetWindowWidth() + kEdge;
    }
    ImGui::End();
}

} // namespace fluid::demo
