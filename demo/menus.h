// fluid-demo — the menus: the F1 help with the controls, and the Esc level menu.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace fluid::demo {

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
