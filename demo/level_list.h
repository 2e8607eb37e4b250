// fluid-demo — the levels the game plays, in order: levels/playlist.txt, then any other level
// file in the directory.
#pragma once
#include <string>
#include <vector>

namespace fluid::demo {

/// One playable level.
struct LevelFile {
    /// File name without ".json" ("dam_break").
    std::string stem;
    /// Full path of the file.
    std::string path;
    /// The file's "name" ("Dam break"); the stem when the file has none or does not parse.
    std::string title;
};

/// The levels of `directory`: those `playlist.txt` names, in its order (one stem per line; `#`
/// starts a comment), then every other `*.json` there, sorted by name. Throws `fluid::Error`
/// naming the file and line when the playlist names a level that does not exist, and when the
/// directory has no level at all. Main thread.
std::vector<LevelFile> listLevels(const std::string& directory);

/// Index of the level `nameOrPath` in `levels`: a stem ("dam_break") or a path whose stem is in
/// the list; -1 if none.
int findLevel(const std::vector<LevelFile>& levels, const std::string& nameOrPath);

} // namespace fluid::demo
