// fluid — region queries: which particles lie in a box or a shape, between steps.
#pragma once

#include <fluid/handle.h>
#include <fluid/shape.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <functional>
#include <span>

namespace fluid {

class World;

/// One particle a region query found.
struct QueryHit {
    /// Its handle (valid until it is removed).
    ParticleHandle handle;
    /// Its index in the world's particle spans (`World::positionX()`...) until the next call
    /// that changes the world (unit: index).
    uint32_t index = 0;
    /// Its material.
    MaterialId material;
};

/// What a region query calls for each particle it finds, in increasing `QueryHit::index`: return
/// true to go on, false to stop there.
using QueryVisitor = std::function<bool(const QueryHit& hit)>;

/// Calls `visit` for each particle whose position lies in `region` (boundary points of a
/// rectangle or circle inside, polygons by the even-odd rule, as `contains`), in increasing
/// array index (the same order for any number of workers, and after a save and load), until it
/// returns false. Returns the particles visited (unit: count). Cost: the cells of the world's
/// query grid the region's bounding box covers, plus the particles in them; the grid is built
/// by the first query after a change to the world (O(particles)), then shared. Throws
/// `fluid::Error` naming the field for a region `validate` refuses, and with
/// `ErrorCode::WrongState` during the world's own step (a plugin's hook). Thread rule: between
/// steps, from any number of threads at once (the world must not change meanwhile).
uint32_t queryParticles(const World& world, const Shape& region, const QueryVisitor& visit);

/// Writes the handles of the particles in `region` to `out`, in increasing array index, at most
/// `out.size()` of them; returns how many lie in the region (unit: count; more than
/// `out.size()` when `out` is too short: the first ones are written). Errors and thread rule
/// as the visitor form.
uint32_t queryParticles(const World& world, const Shape& region, std::span<ParticleHandle> out);

/// Counts the particles in `region` by material: `perMaterial[k]` receives the count of
/// material k for k < `perMaterial.size()` (others are counted in the total only); returns the
/// total (unit: count). Errors and thread rule as the visitor form.
uint32_t countParticles(const World& world, const Shape& region,
                        std::span<uint32_t> perMaterial = {});

/// `queryParticles` over the axis-aligned box [lo, hi] (unit: m; finite, lo <= hi on both
/// axes, a zero-width box allowed), edges included. Errors and thread rule as
/// `queryParticles`.
uint32_t queryBox(const World& world, glm::vec2 lo, glm::vec2 hi, const QueryVisitor& visit);

} // namespace fluid
