// fluid-demo — the files the player writes: one quick save per level (F5 / F9), screenshots.
#pragma once
#include "demo/session.h"

#include <string>

namespace fluid::demo {

/// The quick saves of a folder: one file per level, `<stem>.level`. Main thread.
class QuickSaves {
public:
    /// Saves go to `directory` (created when the first save is made).
    explicit QuickSaves(std::string directory) : m_directory(std::move(directory)) {}

    /// The save of the level `stem`.
    std::string path(const std::string& stem) const;
    /// Whether the level `stem` has a save.
    bool has(const std::string& stem) const;

    /// What a save or a load did: whether it worked, and the toast that says so.
    struct Result {
        /// True when the file was written or read.
        bool ok = false;
        /// "Saved (F9 goes back to it)", "Loaded the save", "Could not save: ...".
        std::string message;
    };
    /// Saves `session` (`Session::save`) and keeps the file (`keepFiles`).
    Result save(const Session& session) const;
    /// Takes `session` back to its save (`Session::restore`); say "No save of this level yet:
    /// F5 saves" when there is none (check `has` first: a grabbed body must be let go before).
    Result load(Session& session) const;

private:
    std::string m_directory;
};

/// Where F12 saves a screenshot of the level `stem` now: `directory/fluid-STEM-YYYYMMDD-HHMMSS.png`
/// (local time).
std::string screenshotPath(const std::string& directory, const std::string& stem);

} // namespace fluid::demo
