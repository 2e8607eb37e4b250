// fluid-demo — the level banner (see banner.h).
#include "demo/banner.h"

#include "demo/ui_common.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <string>

namespace fluid::demo {

namespace {
using namespace ui;
// Widest banner (unit: px; about 100 characters a line), and the room the tuning panel takes
// on the right while it is open.
constexpr float kBannerMaxWidth = 760.0f;
constexpr float kSideRoom = 370.0f;

// `line` cut at a word end so that it and an ellipsis fit in `width` (px, current font).
std::string withEllipsis(std::string_view line, float width) {
    // Three dots: the fonts' glyph ranges (Latin) have no U+2026.
    static constexpr std::string_view kEllipsis = "...";
    std::string_view kept = line;
    while (!kept.empty() && textWidth(std::string(kept) + std::string(kEllipsis)) > width) {
        const size_t space = kept.find_last_of(' ');
        kept = space == std::string_view::npos ? std::string_view{} : kept.substr(0, space);
    }
    while (!kept.empty() &&
           (kept.back() == ' ' || kept.back() == ',' || kept.back() == ':' || kept.back() == ';')) {
        kept.remove_suffix(1);
    }
    return std::string(kept) + std::string(kEllipsis);
}

// "52% / 80%", "312 / 500 particles", "1.20 / 2.00 L".
std::string progressText(const BannerInfo& info) {
    char buffer[96];
    switch (info.measure) {
    case GoalMeasure::Count:
        std::snprintf(buffer, sizeof buffer, "%.0f / %.0f particles", info.goalValue,
                      info.goalAmount);
        break;
    case GoalMeasure::Volume:
        std::snprintf(buffer, sizeof buffer, "%.2f / %.2f L", 1e3 * info.goalValue,
                      1e3 * info.goalAmount);
        break;
    case GoalMeasure::Fraction:
    default:
        std::snprintf(buffer, sizeof buffer, "%.0f%% / %.0f%%", 100.0 * info.goalValue,
                      100.0 * info.goalAmount);
        break;
    }
    return buffer;
}
} // namespace

std::vector<std::string_view> wrapWords(std::string_view text, float width,
                                        const std::function<float(std::string_view)>& measure) {
    std::vector<std::string_view> lines;
    size_t start = 0;
    while (start < text.size()) {
        // Spaces at a line's start belong to no line; a newline ends one.
        while (start < text.size() && text[start] == ' ') {
            ++start;
        }
        if (start >= text.size()) {
            break;
        }
        size_t end = start;    // end of the line so far (exclusive)
        size_t cursor = start; // start of the next word
        bool broken = false;
        while (cursor < text.size()) {
            size_t wordEnd = cursor;
            while (wordEnd < text.size() && text[wordEnd] != ' ' && text[wordEnd] != '\n') {
                ++wordEnd;
            }
            const std::string_view candidate = text.substr(start, wordEnd - start);
            if (end > start && measure(candidate) > width) {
                broken = true; // the word goes to the next line
                break;
            }
            end = wordEnd; // the first word of a line stays on it, even if it is too wide
            if (wordEnd >= text.size() || text[wordEnd] == '\n') {
                break;
            }
            cursor = wordEnd;
            while (cursor < text.size() && text[cursor] == ' ') {
                ++cursor;
            }
        }
        lines.push_back(text.substr(start, end - start));
        start = end;
        if (!broken && start < text.size() && text[start] == '\n') {
            ++start;
        }
    }
    return lines;
}

void drawLevelBanner(const BannerInfo& info, ImFont* big, const OverlayLayout& layout,
                     float hudRight) {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float screenWidth = viewport->WorkSize.x;
    const float kEdge = layout.edge;
    // Between the HUD and the window's right edge (the tuning panel's left edge while it is
    // open), centred on the window when that fits, else centred in the room; on a tiny window
    // over everything.
    const float roomLeft = std::max(hudRight + kEdge, kEdge);
    const float roomRight = screenWidth - kEdge - (info.panelOpen ? kSideRoom : 0.0f);
    float width = std::min(kBannerMaxWidth, roomRight - roomLeft);
    float left = 0.5f * (screenWidth - width);
    if (left < roomLeft || left + width > roomRight) {
        left = roomLeft + 0.5f * (roomRight - roomLeft - width);
    }
    if (width < 240.0f * layout.scale) {
        width = std::max(std::min(kBannerMaxWidth, screenWidth - 2.0f * kEdge), 1.0f);
        left = 0.5f * (screenWidth - width);
    }
    ImGui::SetNextWindowPos(
        ImVec2(viewport->WorkPos.x + left, viewport->WorkPos.y + layout.banner.min.y));
    ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, FLT_MAX));
    ImGui::SetNextWindowBgAlpha(kOverlayBackground);
    const HintColour hints;
    if (ImGui::Begin("##banner", nullptr, kOverlayFlags)) {
        const ImGuiStyle& style = ImGui::GetStyle();
        float used = 2.0f * style.WindowPadding.y;
        {
            const BigFont font(big, layout.scale);
            centredText(info.name);
            used += ImGui::GetTextLineHeightWithSpacing();
        }
        ImGui::SetWindowFontScale(layout.scale);
        const bool goal = info.state != GoalState::None;
        if (goal) {
            // The progress bar (the clock in its label) and the spacing above it.
            used += ImGui::GetFrameHeightWithSpacing() + style.ItemSpacing.y;
        }
        if (!info.text.empty()) {
            // As many lines as the band above the level holds (none when the title and the
            // progress bar fill it), broken at spaces only; a cut text ends in an ellipsis.
            const float avail = ImGui::GetContentRegionAvail().x;
            const std::vector<std::string_view> lines = wrapWords(info.text, avail, textWidth);
            const float budget = layout.banner.height();
            const size_t fit = static_cast<size_t>(
                std::max((budget - used) / ImGui::GetTextLineHeightWithSpacing(), 0.0f));
            const size_t shown = std::min(lines.size(), fit);
            for (size_t k = 0; k < shown; ++k) {
                std::string line(lines[k]);
                if (k + 1 == shown && shown < lines.size()) {
                    line = withEllipsis(lines[k], avail);
                }
                // One line is centred under the title; a paragraph is left-aligned.
                if (lines.size() == 1) {
                    centredText(line);
                } else {
                    text(line);
                }
            }
        }
        if (goal) {
            ImGui::Spacing();
            const double fraction = info.goalAmount > 0.0
                                        ? std::clamp(info.goalValue / info.goalAmount, 0.0, 1.0)
                                        : 0.0;
            const ImVec4 bar = info.state == GoalState::Won    ? kGreen
                               : info.state == GoalState::Lost ? kRed
                                                               : ImVec4(0.26f, 0.59f, 0.98f, 1.0f);
            // "312 / 500 particles    time left 41.2 s" (amber under 10 s), or the time played.
            std::string label = progressText(info);
            char clock[64];
            bool hurry = false;
            if (info.timeLimit > 0.0) {
                const double remaining = std::max(info.timeLimit - info.time, 0.0);
                std::snprintf(clock, sizeof clock, "    time left %.1f s", remaining);
                hurry = remaining < 10.0 && info.state == GoalState::Pending;
            } else {
                std::snprintf(clock, sizeof clock, "    time %.1f s", info.time);
            }
            label += clock;
            ImGui::PushStyleColor(ImGuiCol_PlotHistogram, bar);
            if (hurry) {
                ImGui::PushStyleColor(ImGuiCol_Text, kAmber);
            }
            ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1.0f, 0.0f), label.c_str());
            ImGui::PopStyleColor(hurry ? 2 : 1);
        }
        ImGui::SetWindowFontScale(1.0f);
    }
    ImGui::End();

    if (info.state != GoalState::Won && info.state != GoalState::Lost) {
        return;
    }
    const bool won = info.state == GoalState::Won;
    ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.7f);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(28.0f, 18.0f));
    if (ImGui::Begin("##outcome", nullptr, kOverlayFlags)) {
        {
            const BigFont font(big, 1.5f);
            ImGui::PushStyleColor(ImGuiCol_Text, won ? kGreen : kRed);
            centredText(won ? "Level complete!" : "Time's up");
            ImGui::PopStyleColor();
        }
        ImGui::Spacing();
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        centredText("R retry, N next level");
        ImGui::PopStyleColor();
    }
    ImGui::End();
    ImGui::PopStyleVar();
}

} // namespace fluid::demo
