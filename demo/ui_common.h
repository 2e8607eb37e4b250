// fluid-demo — what the ImGui overlays share: colours, window flags and text helpers.
#pragma once

#include <imgui.h>

#include <string_view>

namespace fluid::demo::ui {

/// Amber: warnings (PAUSED, "simulation behind", a clock under 10 s).
inline const ImVec4 kAmber{1.00f, 0.72f, 0.20f, 1.0f};
/// Green: a goal reached.
inline const ImVec4 kGreen{0.40f, 0.92f, 0.45f, 1.0f};
/// Red: errors, a goal lost.
inline const ImVec4 kRed{1.00f, 0.38f, 0.33f, 1.0f};
/// Cyan: zero-g.
inline const ImVec4 kCyan{0.45f, 0.85f, 1.00f, 1.0f};
/// Light blue: keys in the help, the current level in the menu.
inline const ImVec4 kKey{0.62f, 0.80f, 1.00f, 1.0f};
/// Labels and hints of the HUD and the banner: light enough to read over the grey walls
/// through the overlays' dark backing (ImGui's own disabled grey, 0.5, is not).
inline const ImVec4 kHint{0.70f, 0.73f, 0.78f, 1.0f};
/// Opacity of the HUD's and the banner's backing: dark enough that text stays readable over
/// walls, water and yoghurt (unit: 1).
inline constexpr float kOverlayBackground = 0.82f;
/// Size the banner title is drawn at when the bridge found no TrueType font (unit: px).
inline constexpr float kBannerSize = 28.0f;
/// Margin between the overlays and the window's edges (unit: px).
inline constexpr float kEdge = 10.0f;
/// Flags of the overlays that take no input (HUD, banner, outcome, toast).
inline constexpr ImGuiWindowFlags kOverlayFlags =
    ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
    ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoMove;

/// Draws `s` as one unformatted line (an empty view may hold a null pointer, which ImGui's
/// text functions must not get).
void text(std::string_view s);
/// Width of `s` in the current font (unit: px).
float textWidth(std::string_view s);
/// Draws `s` centred in the window's remaining width.
void centredText(std::string_view s);

/// Draws with the banner font while it lives: `big` when it is a real large font, else the
/// current font scaled up to kBannerSize times `scale`. Restores the font on destruction.
class BigFont {
public:
    /// Pushes the font (and scale) for the current window.
    BigFont(ImFont* big, float scale);
    /// Pops what the constructor pushed.
    ~BigFont();
    /// Not copyable: it pairs a push with a pop.
    BigFont(const BigFont&) = delete;
    /// Not assignable either.
    BigFont& operator=(const BigFont&) = delete;

private:
    bool m_pushed = false;
    bool m_scaled = false;
};

/// Pushes the hint colour as ImGui's disabled text colour for the overlays' labels while it
/// lives.
class HintColour {
public:
    /// Pushes the colour.
    HintColour() { ImGui::PushStyleColor(ImGuiCol_TextDisabled, kHint); }
    /// Pops it.
    ~HintColour() { ImGui::PopStyleColor(); }
    /// Not copyable: it pairs a push with a pop.
    HintColour(const HintColour&) = delete;
    /// Not assignable either.
    HintColour& operator=(const HintColour&) = delete;
};

} // namespace fluid::demo::ui
