// fluid — queries between steps: which particles lie in a box or a shape, where a ray meets the
// liquid, and what the liquid is like at a point.
#pragma once

#include <fluid/handle.h>
#include <fluid/shape.h>
#include <fluid/surface_field.h>

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

// ---- Ray casts and the liquid at a point ------------------------------------------------------
// The liquid here is the drawn one: where the `SurfaceField` (fluid/surface_field.h) is at least
// its threshold, the surface fluid::gl's metaball view draws with the same settings (solids'
// lowered level aside: that is a picture-only effect next to walls and bodies).

/// Where a ray first meets the liquid (`rayCast`).
struct RayHit {
    /// True when the ray meets the liquid between its ends; the other fields are set only then.
    bool hit = false;
    /// True when the ray's start lies in the liquid: then `fraction` is 0, `point` the start and
    /// `normal` (0, 0).
    bool startsInside = false;
    /// Where the ray enters the liquid (unit: m), within 0.01 of the finest spacing of the
    /// field's crossing along the ray.
    glm::vec2 point{0.0f, 0.0f};
    /// The surface's outward unit normal there: minus the field's gradient, normalised (unit: 1;
    /// against the ray where the gradient vanishes).
    glm::vec2 normal{0.0f, 0.0f};
    /// How far along the ray: `point = p1 + fraction (p2 - p1)` (unit: 1; [0, 1]).
    float fraction = 0.0f;
    /// The material of `particle`.
    MaterialId material;
    /// The nearest particle to `point` among those whose kernel reaches it (ties: the lowest
    /// index), valid until it is removed.
    ParticleHandle particle;
    /// Its index in the world's particle spans until the world changes (unit: index).
    uint32_t index = 0;
};

/// The first point where the segment p1 -> p2 (unit: m; finite) enters the liquid as `field`
/// draws it; a ray that starts inside reports that (`RayHit::startsInside`, fraction 0); a ray
/// of zero length hits when its point is in the liquid. The result is the same for any number of
/// workers and after a save and load. Cost: the query grid's cells along the ray (and the
/// particles around those near the liquid); the grid is built by the first query after a change
/// (`queryParticles`). Throws `fluid::Error` naming the value for a non-finite end or a field
/// `validate` refuses, and with `ErrorCode::WrongState` during the world's own step. Thread
/// rule: between steps, from any number of threads at once (the world must not change
/// meanwhile).
RayHit rayCast(const World& world, glm::vec2 p1, glm::vec2 p2, const SurfaceField& field = {});

/// A particle a ray passes within the radius of (`rayCastParticles`).
struct RayParticleHit {
    /// Its handle (valid until it is removed).
    ParticleHandle handle;
    /// Its index in the world's particle spans until the world changes (unit: index).
    uint32_t index = 0;
    /// Its material.
    MaterialId material;
    /// Where the ray enters the circle of the radius round it (unit: m); the ray's start when it
    /// starts inside the circle.
    glm::vec2 point{0.0f, 0.0f};
    /// From the particle to `point`, normalised (unit: 1; (0, 0) when they coincide).
    glm::vec2 normal{0.0f, 0.0f};
    /// How far along the ray `point` is (unit: 1; [0, 1]).
    float fraction = 0.0f;
};

/// What `rayCastParticles` calls for each particle, in increasing `fraction` (ties: increasing
/// index). Its return value steers the cast as LiquidFun's and Box2D's ray casts: negative (-1)
/// ignores this particle and goes on, 0 stops, a fraction in (0, 1) clips the ray there (no
/// particle beyond it is reported), 1 (or more) goes on unclipped. Return the hit's own
/// fraction to find the closest particle. NaN is refused.
using RayVisitor = std::function<float(const RayParticleHit& hit)>;

/// Calls `visit` (which must not change the world) for each particle whose circle of `radius`
/// (unit: m; finite, > 0; the material's spacing is a good choice) the segment p1 -> p2 (unit:
/// m; finite) passes through, in increasing fraction, until it returns 0 or the ray is clipped
/// short of the next one. Returns
/// the particles visited (unit: count). Cost: the query grid's cells within `radius` of the
/// ray. Throws `fluid::Error` naming the value for a non-finite end, a bad radius, an empty
/// visitor or a NaN returned by it, and with `ErrorCode::WrongState` during the world's own
/// step. Thread rule: as `rayCast`.
uint32_t rayCastParticles(const World& world, glm::vec2 p1, glm::vec2 p2, float radius,
                          const RayVisitor& visit);

/// The liquid at a point (`sample`). The interpolated values are Shepard-normalised sums over
/// the particles within their material's smoothing distance, weighted by the solvers' kernel
/// (Wendland C2) times each particle's rest area; they are 0 where no particle reaches.
struct LiquidSample {
    /// True where the drawn liquid is (the field at least its threshold).
    bool inLiquid = false;
    /// The field at the point (unit: 1; see `SurfaceField`).
    float field = 0.0f;
    /// Density over the particles' rest density, interpolated (unit: 1; about 1 in the liquid
    /// after a step, 0 before the first step).
    float densityRatio = 0.0f;
    /// Pressure, interpolated (unit: Pa; `World::pressure`'s).
    float pressure = 0.0f;
    /// Velocity, interpolated (unit: m/s).
    glm::vec2 velocity{0.0f, 0.0f};
    /// Depth below the free surface straight up: how far up the liquid goes before the field
    /// falls below its threshold (the upward ray cast; an air pocket above counts as the
    /// surface) (unit: m; 0 when not `inLiquid`).
    float depth = 0.0f;
    /// The material with the largest share (ties: the lowest index); meaningful when
    /// `neighbours` > 0.
    MaterialId material;
    /// Particles whose kernel reaches the point (unit: count).
    uint32_t neighbours = 0;
};

/// The liquid at `point` (unit: m; finite): in it or not (the drawn surface, `field`), the
/// density ratio, pressure and velocity interpolated from the particles around it, and the depth
/// below the free surface above it. `materialFractions[k]` receives material k's share of the
/// interpolation weight for k < its size (unit: 1; they sum to 1 where `neighbours` > 0, else
/// 0; entries past the world's materials receive 0). Errors and thread rule as `rayCast`. Cost: the query grid's cells around the point, and
/// the cells up to the surface for the depth.
LiquidSample sample(const World& world, glm::vec2 point, std::span<float> materialFractions = {},
                    const SurfaceField& field = {});

} // namespace fluid
