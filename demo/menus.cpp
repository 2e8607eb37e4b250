// fluid-demo — the menus (see menus.h).
#include "demo/menus.h"

#include "demo/banner.h"
#include "demo/ui_common.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstddef>

namespace fluid::demo {

namespace {
using namespace ui;
// Width the help window wraps the level's text at (unit: px; about the controls table's).
constexpr float kHelpTextWidth = 440.0f;

constexpr std::array<ControlHelp, 21> kControls{{
    {"S", "Cycle views: metaballs, pressure, particles"},
    {"G", "Gravity on / zero-g"},
    {"Left drag", "Push the fluid"},
    {"Right drag", "Pull the fluid"},
    {"Shift + left drag", "Grab a body"},
    {"Q / E (grabbing)", "Turn a grabbed plank"},
    {"Space", "Drop a blob of the current material"},
    {"M", "Switch material (water / yoghurt)"},
    {"L", "Laser from the cursor: where it meets the liquid, and the normal"},
    {"Ctrl + click", "Drop a crate (levels with bodies)"},
    {"R", "Reset the level"},
    {"P", "Pause / resume"},
    {". (period)", "Step one frame while paused"},
    {"N / B", "Next / previous level"},
    {"1 - 9", "Jump to a level"},
    {"Tab", "Tuning panel"},
    {"F5 / F9", "Save the level / go back to the save"},
    {"F1", "This help"},
    {"F11", "Fullscreen"},
    {"F12", "Screenshot"},
    {"Esc", "Level menu"},
}};
} // namespace

std::span<const ControlHelp> controls() {
    return kControls;
}

void drawHelp(bool* open, std::string_view levelName, std::string_view levelText) {
    if (open == nullptr || !*open) {
        return;
    }
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.92f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;
    if (ImGui::Begin("Controls (F1)", open, flags)) {
        if (!levelName.empty()) {
            // The level's whole text, which the banner may have cut.
            ImGui::PushStyleColor(ImGuiCol_Text, kKey);
            text(levelName);
            ImGui::PopStyleColor();
            for (const std::string_view line : wrapWords(levelText, kHelpTextWidth, textWidth)) {
                text(line);
            }
            ImGui::Spacing();
            ImGui::Separator();
            ImGui::Spacing();
        }
        const ImGuiTableFlags tableFlags =
            ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_PadOuterX;
        if (ImGui::BeginTable("controls", 2, tableFlags)) {
            for (const ControlHelp& control : kControls) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::PushStyleColor(ImGuiCol_Text, kKey);
                text(control.keys);
                ImGui::PopStyleColor();
                ImGui::TableNextColumn();
                text(control.action);
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

int drawLevelMenu(std::span<const LevelEntry> levels, int current, bool* open) {
    if (open == nullptr || !*open) {
        return -1;
    }
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.94f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;
    int chosen = -1;
    if (ImGui::Begin("Levels (Esc)", open, flags)) {
        // Column of the dimmed file stems: after the longest title.
        float titleWidth = 0.0f;
        for (const LevelEntry& level : levels) {
            const std::string& title = level.title.empty() ? level.stem : level.title;
            titleWidth = std::max(titleWidth, ImGui::CalcTextSize(title.c_str()).x);
        }
        const float numberWidth = ImGui::CalcTextSize("00 ").x;
        const float stemX = ImGui::GetCursorPosX() + numberWidth + titleWidth + 40.0f;
        for (std::size_t i = 0; i < levels.size(); ++i) {
            const LevelEntry& level = levels[i];
            const std::string& title = level.title.empty() ? level.stem : level.title;
            ImGui::PushID(static_cast<int>(i));
            const float rowX = ImGui::GetCursorPosX();
            const bool isCurrent = static_cast<int>(i) == current;
            // Width 0: the row spans the window, whose width the stems and buttons set.
            if (ImGui::Selectable("##level", isCurrent)) {
                chosen = static_cast<int>(i);
            }
            ImGui::SameLine(rowX);
            ImGui::TextDisabled("%zu", i + 1);
            ImGui::SameLine(rowX + numberWidth);
            if (isCurrent) {
                ImGui::TextColored(kKey, "%s", title.c_str());
            } else {
                text(title);
            }
            ImGui::SameLine(stemX);
            ImGui::TextDisabled("%s", level.stem.c_str());
            ImGui::PopID();
        }
        if (levels.empty()) {
            ImGui::TextDisabled("no level files found");
        }
        ImGui::Spacing();
        ImGui::Separator();
        ImGui::Spacing();
        if (ImGui::Button("Resume")) {
            *open = false;
        }
        ImGui::SameLine();
        if (ImGui::Button("Quit")) {
            chosen = -2;
        }
        ImGui::SameLine();
        ImGui::TextDisabled("  1-9 jump, N / B next / previous");
    }
    ImGui::End();
    if (chosen >= 0) {
        *open = false;
    }
    return chosen;
}

} // namespace fluid::demo
