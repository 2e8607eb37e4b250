// fluid-demo — the ImGui panels: HUD, level banner, help, level menu, tuning panel, toast.
#pragma once

#include <fluid/level.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

struct ImFont;

namespace fluid::demo {

/// What the HUD shows; the main loop fills it every frame.
struct HudInfo {
    /// Rendered frames per second (unit: Hz).
    float fps = 0.0f;
    /// Particles in the world (unit: count).
    uint32_t particles = 0;
    /// Wall time the simulation took this frame, all its steps (unit: ms).
    float simMsPerFrame = 0.0f;
    /// Solver sub-steps of the last step (unit: count; `Profile::substeps`).
    uint32_t substeps = 0;
    /// Name of the current view ("metaballs", "pressure", "particles").
    std::string_view view;
    /// Name of the material Space drops.
    std::string_view material;
    /// True while gravity is off (G).
    bool zeroG = false;
    /// True while paused (P).
    bool paused = false;
    /// `FramePacer::behind()`: shows the amber "simulation behind" line.
    bool behind = false;
    /// `FramePacer::speed()` (unit: 1; 1 = real time).
    double speed = 1.0;
    /// `FramePacer::droppedSteps()` (unit: count).
    uint64_t droppedSteps = 0;
    /// The liquid under the cursor (`LiquidProbe::cursorText`; empty: no line).
    std::string_view cursor;
    /// The laser's hit (`LiquidProbe::laserText`; empty while it is off: no line).
    std::string_view laser;
};

/// Draws the HUD top-left: fps, particles, sim ms/frame, sub-steps, view, material, gravity or
/// zero-g, the liquid under the cursor and the laser's hit, PAUSED, and "simulation behind: 71% speed" in amber while `behind`. Labels and hints
/// are a light grey on an 82% opaque backing, readable over the grey walls. No decoration,
/// takes no input; `drawLevelBanner` keeps clear of its right edge (as measured when last
/// drawn). Thread rule (every function here): between `ImGuiBridge::newFrame` and `render`,
/// on the GL thread.
void drawHud(const HudInfo& info);

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

/// Draws the banner at the top, between the HUD and the window's right edge (the tuning panel
/// while it is open), centred on the window when it fits: the title in `big`
/// (`ImGuiBridge::bannerFont()`; nullptr or a font under 20 px is scaled up), the text wrapped
/// at spaces only (`wrapWords`: a number such as "5,000" or a word never splits), and with a
/// goal a progress bar (value / amount) whose label also holds the time left (amber under
/// 10 s) or played. The banner stays within the top 19% of the window, the room
/// `Session::camera` leaves above the level: a text with more lines than fit is cut at a word
/// with "..." (the F1 help shows it whole). When the goal is Won or Lost, also a large centred
/// "Level complete!" (green) or "Time's up" (red) over "R retry, N next level". Takes no input.
/// To fade it out, wrap the call in `ImGui::PushStyleVar(ImGuiStyleVar_Alpha, a)`.
void drawLevelBanner(const BannerInfo& info, ImFont* big);

/// Splits `text` into lines at most `width` wide (unit: as `measure`, e.g. px), breaking only
/// at spaces and at newlines: a number ("5,000", "2.5"), a hyphenated or any other word stays
/// whole; a word wider than `width` gets a line of its own. Runs of spaces at a break are
/// dropped. `measure` gives the width of a piece of text (ImGui's text width in the game).
/// The views point into `text`. Thread rule: any thread (pure, given a pure `measure`).
std::vector<std::string_view> wrapWords(std::string_view text, float width,
                                        const std::function<float(std::string_view)>& measure);

/// Draws the F1 overlay listing every control, centred; its close button clears `*open`.
/// With a `levelName`, it first shows the level's title and whole `levelText` (wrapped as the
/// banner's, which may cut it). Nothing is drawn while `*open` is false.
void drawHelp(bool* open, std::string_view levelName = {}, std::string_view levelText = {});

/// One entry of the level menu.
struct LevelEntry {
    /// File stem ("dam_break"), shown dimmed.
    std::string stem;
    /// Title from the file ("Dam break"); the stem is shown when empty.
    std::string title;
};

/// Draws the Esc menu, centred: the levels numbered from 1 (the current one highlighted), then
/// "Resume" and "Quit". Returns the index clicked (and clears `*open`), -2 for Quit, or -1.
/// "Resume" or the close button clear `*open`. Nothing is drawn while `*open` is false.
int drawLevelMenu(std::span<const LevelEntry> levels, int current, bool* open);

/// Draws the Tab panel on the right, built from what the level's world declares:
/// - Solver: the quality presets (game, precise) and the position-based solver's sub-steps,
///   iterations, viscosity interval, coarse correction and vorticity
///   (`World::setPositionBased`), and the last step's density error.
/// - Every plugin of `world.forces()` and `world.boundaries()`: a header with its name in the
///   level file and its type; every number parameter as a drag field within its declared range
///   (tooltip: description, unit, range); point lists shown read-only as a count. A refused value
///   (`Plugin::setParam` throws) shows the error in red under the field. Changing a
///   `force.gravity` parameter also sets the Box2D world's gravity (the sum of the world's
///   force.gravity plugins, as the loader does) and wakes the bodies, so buoyancy follows.
/// - Every material of `level.materials`: viscosity, surface tension, stiffness, rest density,
///   mass and smoothing distance (`World::setMaterial`, errors in red as above).
/// Call between steps. Its close button clears `*open`; nothing is drawn while it is false.
void drawTuningPanel(Level& level, bool* open);

/// Draws a short message bottom-centre (errors such as "world full"), at opacity `alpha`
/// (unit: 1; range [0, 1]) so the caller can fade it out. Takes no input.
void drawToast(std::string_view message, float alpha = 1.0f);

/// The controls `drawHelp` lists, in order: key and action (for docs and tests).
struct ControlHelp {
    /// Key or mouse gesture, e.g. "Shift + left drag".
    std::string_view keys;
    /// What it does.
    std::string_view action;
};
/// Every control of the demo (unit: entries).
std::span<const ControlHelp> controls();

} // namespace fluid::demo
