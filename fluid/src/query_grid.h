// fluid — what the queries share (query.cpp, ray.cpp): the refusal during a step and the query
// grid, built on the first query after a change to the world.
#pragma once

#include "world_state.h"

namespace fluid::detail {

/// The world's state for reading; throws `fluid::Error` (ErrorCode::WrongState) "<function>:
/// called during the world's own step ..." while the world steps. Queries change nothing but the
/// shared grid's cache.
WorldState& queryState(const World& world, const char* function);

/// The grid over the particles as they stand now (cells of the largest smoothing distance),
/// with their bounding box; built under the grid's lock if the world changed since the last
/// one. Call only with particles in the world.
const WorldState::QueryGrid& queryGrid(WorldState& s);

} // namespace fluid::detail
