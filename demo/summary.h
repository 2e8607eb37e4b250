// fluid-demo — the line a scripted run ends with: the game's state, and a hash of its bits.
#pragma once
#include "demo/session.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace fluid::demo {

/// FNV-1a (64 bit, the checksum of saves) over every particle's position and velocity, in the
/// world's order, then every Box2D body's position, angle and velocities, in the level's
/// order: two runs that print the same hash stepped the same bits (a desktop and a browser).
uint64_t stateHash(const Level& level);

/// What a scripted run's summary line holds besides the session.
struct SummaryInfo {
    /// Frames played (unit: count).
    uint32_t frames = 0;
    /// The view shown ("metaballs").
    std::string_view view;
    /// True while paused.
    bool paused = false;
    /// `LiquidProbe::summary()`: the probe's and the laser's fields, each with a leading space.
    std::string_view probe;
};

/// "level=... frames=... time=... particles=... m_water=... cx=... cy=... view=... gravity=on
/// material=water paused=0 bodies=... goal=... goal_value=... b_NAME=X,Y ... probe=... hash=..."
/// (docs/demo.md, "Scripted input"), without the "fluid-demo: " the game prints before it.
std::string summaryLine(const Session& session, const SummaryInfo& info);

} // namespace fluid::demo
