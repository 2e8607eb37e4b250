// fluid::c — ray casts and the liquid at a point (fluid/c.h, fluid/query.h).
#include "c_internal.h"

#include <fluid/query.h>
#include <fluid/surface_field.h>

#include <fluid/internal/checks.h>

#include <cmath>
#include <span>
#include <string>

using namespace fluid;
using namespace fluid::c;

namespace {

// The C field settings, or the defaults for NULL; INVALID_ARGUMENT naming the C field.
SurfaceField fieldOf(const fluid_surface_field* field, const char* function) {
    SurfaceField f;
    if (field != nullptr) {
        f.fieldRadius = field->field_radius;
        f.threshold = field->threshold;
        const std::string prefix = std::string(function) + ": field->";
        internal::checkRange(prefix, "field_radius", f.fieldRadius, SurfaceField::kMinRadius,
                             SurfaceField::kMaxRadius, "1");
        internal::checkRange(prefix, "threshold", f.threshold, SurfaceField::kMinThreshold,
                             SurfaceField::kMaxThreshold, "1");
    }
    return f;
}

// `point`, or INVALID_ARGUMENT naming it when it is not finite.
glm::vec2 pointOf(fluid_vec2 point, const char* function, const char* name) {
    if (!std::isfinite(point.x) || !std::isfinite(point.y)) {
        throw Failure{FLUID_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + name + " = (" +
                                                        internal::formatValue(point.x) + ", " +
                                                        internal::formatValue(point.y) +
                                                        ") is not finite (unit: m)"};
    }
    return toVec(point);
}

} // namespace

fluid_surface_field fluid_default_surface_field(void) {
    const SurfaceField f;
    return {f.fieldRadius, f.threshold};
}

fluid_status fluid_world_ray_cast(const fluid_world* world, fluid_vec2 p1, fluid_vec2 p2,
                                  const fluid_surface_field* field, fluid_ray_hit* hit) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_ray_cast";
        const World& w = worldOf(world, function);
        need(hit, function, "hit");
        const glm::vec2 a = pointOf(p1, function, "p1"), b = pointOf(p2, function, "p2");
        const RayHit r = rayCast(w, a, b, fieldOf(field, function));
        *hit = fluid_ray_hit{r.hit,      r.startsInside,  toC(r.point),    toC(r.normal),
                             r.fraction, toC(r.material), toC(r.particle), r.index};
    });
}

fluid_status fluid_world_ray_cast_particles(const fluid_world* world, fluid_vec2 p1, fluid_vec2 p2,
                                            float radius, fluid_ray_visitor visit, void* user,
                                            uint32_t* visited) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_ray_cast_particles";
        const World& w = worldOf(world, function);
        need(reinterpret_cast<const void*>(visit), function, "visit");
        const glm::vec2 a = pointOf(p1, function, "p1"), b = pointOf(p2, function, "p2");
        if (!(radius > 0.0f) || !std::isfinite(radius)) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          std::string(function) + ": radius = " + internal::formatValue(radius) +
                              " is out of range (0, inf) (unit: m)"};
        }
        const uint32_t n = rayCastParticles(w, a, b, radius, [&](const RayParticleHit& h) {
            const fluid_ray_particle_hit c{toC(h.handle), h.index,       toC(h.material),
                                           toC(h.point),  toC(h.normal), h.fraction};
            const float f = visit(user, &c);
            if (std::isnan(f)) {
                throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                              std::string(function) +
                                  ": the visitor returned nan; expected -1 (ignore the "
                                  "particle), 0 (stop), a fraction in (0, 1) (clip the ray) "
                                  "or 1 (go on)"};
            }
            return f;
        });
        if (visited != nullptr) {
            *visited = n;
        }
    });
}

fluid_status fluid_world_sample(const fluid_world* world, fluid_vec2 point,
                                const fluid_surface_field* field, float* material_fractions,
                                uint32_t material_count, fluid_liquid_sample* sample) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_sample";
        const World& w = worldOf(world, function);
        need(sample, function, "sample");
        if (material_count > 0) {
            need(material_fractions, function, "material_fractions");
        }
        const glm::vec2 at = pointOf(point, function, "point");
        const SurfaceField f = fieldOf(field, function);
        const LiquidSample s =
            fluid::sample(w, at, std::span<float>(material_fractions, material_count), f);
        *sample = fluid_liquid_sample{s.inLiquid,      s.field, s.densityRatio,  s.pressure,
                                      toC(s.velocity), s.depth, toC(s.material), s.neighbours};
    });
}
