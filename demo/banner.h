// fluid-demo — the level banner (title, text, goal progress), the outcome, word wrapping.
#pragma once

#include "demo/layout.h"

#include <fluid/level.h>

#include <functional>
#include <string_view>
#include <vector>

struct ImFont;

namespace fluid::demo {

/// What the level banner shows.
struct BannerInfo {
    /// Level title (`Level::name`).
    std::string_view name;
    /// The level's description or its goal's text.
    std::string_view text;
    /// `Level::goalState()`; `None` hides the goal line.
    GoalState state = GoalState::None;
    /// `Level::goalValue()` (unit: per `measure`).
    double goalValue = 0.0;
    /// `Level::goal.amount` (unit: per `measure`; > 0 with a goal).
    double goalAmount = 0.0;
    /// `Level::goal.measure`: the progress reads "52% / 80%", "312 / 500 particles" or
    /// "1.20 / 2.00 L" (volume shown in litres).
    GoalMeasure measure = GoalMeasure::Fraction;
    /// Simulated time (unit: s; `World::time()`).
    double time = 0.0;
    /// `Level::goal.timeLimit` (unit: s; 0 = none: the elapsed time is shown instead of the
    /// time left).
    double timeLimit = 0.0;
    /// True while the tuning panel is open on the right: the banner keeps clear of it.
    bool panelOpen = false;
};

/// Draws the banner at the top of `layout.banner`, between `hudRight` (unit: px; the HUD's
/// right edge, `drawHud`) plus a margin and the window's right edge (the tuning panel while it
/// is open), centred on the window when it fits: the title in `big`
/// (`ImGuiBridge::bannerFont()`; nullptr or a font under 20 px is scaled up), the text wrapped
/// at spaces only (`wrapWords`: a number such as "5,000" or a word never splits), and with a
/// goal a progress bar (value / amount) whose label also holds the time left (amber under
/// 10 s) or played; all at `layout.scale`. The banner stays within `layout.banner`, in the
/// band above the level (`frameLevel`): a text with more lines than fit is cut at a word
/// with "..." (the F1 help shows it whole). When the goal is Won or Lost, also a large centred
/// "Level complete!" (green) or "Time's up" (red) over "R retry, N next level". Takes no input.
/// To fade it out, wrap the call in `ImGui::PushStyleVar(ImGuiStyleVar_Alpha, a)`.
void drawLevelBanner(const BannerInfo& info, ImFont* big, const OverlayLayout& layout,
                     float hudRight);

/// Splits `text` into lines at most `width` wide (unit: as `measure`, e.g. px), breaking only
/// at spaces and at newlines: a number ("5,000", "2.5"), a hyphenated or any other word stays
/// whole; a word wider than `width` gets a line of its own. Runs of spaces at a break are
/// dropped. `measure` gives the width of a piece of text (ImGui's text width in the game).
/// The views point into `text`. Thread rule: any thread (pure, given a pure `measure`).
std::vector<std::string_view> wrapWords(std::string_view text, float width,
                                        const std::function<float(std::string_view)>& measure);

} // namespace fluid::demo
