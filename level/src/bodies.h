// fluid::level — private: the Box2D part of the level format (docs/levels.md, "bodies",
// "joints", "coupling"): reads it strictly and builds the b2World, its bodies and joints, and the
// coupling with the level's world.
#pragma once

#include "json_positions.h"

#include <fluid/level.h>

namespace fluid::detail {

/// Reads the top-level keys "bodies", "joints" and "coupling" of the level object `root` and
/// builds them into `level`: `physics` (only when there is at least one body), `bodies`,
/// `joints` and `coupling`. Call it after the world, its materials and plugins are built: Box2D's
/// gravity is the sum of the world's `force.gravity` plugins, `densityRatio` reads the first
/// material, and the coupling's boundary plugin joins after the file's own boundaries. Throws
/// LevelError for anything the file gets wrong; no bad value reaches a Box2D assertion.
/// Thread rule: one thread.
void readBodies(const JsonDocument& doc, const ObjectReader& root, Level& level);

} // namespace fluid::detail
