// fluid-demo — the Tab tuning panel: solver, plugins and materials of the level's world.
#pragma once

#include <fluid/level.h>

namespace fluid::demo {

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

} // namespace fluid::demo
