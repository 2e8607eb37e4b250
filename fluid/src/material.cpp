// fluid — materials: the seed's Table 4.1 presets and validation.
#include <fluid/error.h>
#include <fluid/internal/checks.h>
#include <fluid/material.h>

#include <cmath>
#include <sstream>

namespace fluid {

Material water() {
    Material m;
    m.mass = 0.013f;
    m.restDensity = 1000.0f;
    m.viscosity = 3.5f;
    m.stiffness = 3.0f;
    m.smoothingDistance = 0.032f;
    m.kernelParticles = 32.0f;
    m.surfaceTension = 0.1f;
    m.name = "water";
    return m;
}

Material seedYoghurt() {
    Material m;
    m.mass = 0.014f;
    m.restDensity = 1050.0f;
    m.viscosity = 20.0f;
    m.stiffness = 5.0f;
    m.smoothingDistance = 0.04f;
    m.kernelParticles = 50.0f;
    m.surfaceTension = 0.1f;
    m.name = "seed_yoghurt";
    return m;
}

Material yoghurt() {
    Material m = seedYoghurt();
    m.yieldStress = 400.0f;
    m.consistency = 2.0f;
    m.flowIndex = 0.7f;
    m.shearModulus = 0.0f;
    m.name = "yoghurt";
    return m;
}

namespace {

// In the order snapshots store them (snapshot.cpp reads and writes this table).
constexpr MaterialField kFields[] = {
    {"mass", &Material::mass, nullptr, "kg", 0.0, 1e3, true,
     "Mass of one particle; with the rest density it sets the particle spacing."},
    {"restDensity", &Material::restDensity, nullptr, "kg/m^3", 0.0, 1e5, true,
     "Density at rest; with the mass it sets the particle spacing."},
    {"viscosity", &Material::viscosity, nullptr, "Pa*s", 0.0, 1e4, false,
     "Dynamic viscosity mu (seed eq. 2.6); with a yield stress, the flow law's high-shear limit."},
    {"stiffness", &Material::stiffness, nullptr, "J/kg", 0.0, 1e8, true,
     "k of the linear equation of state p = k (rho - rho0); sqrt(k) is Tait's sound-speed floor."},
    {"smoothingDistance", &Material::smoothingDistance, nullptr, "m", 3e-3, 0.4, false,
     "Kernel support radius h: how far particles feel each other; 3 to 8 particle spacings."},
    {"kernelParticles", &Material::kernelParticles, nullptr, "count", 4.0, 400.0, false,
     "Particles in the support the material was tuned for (informational)."},
    {"surfaceTension", &Material::surfaceTension, nullptr, "m^3/(kg s^2)", 0.0, 0.5, false,
     "Cohesion gamma [Akinci 2013]: holds drops and blobs together; 0 is off."},
    {"yieldStress", &Material::yieldStress, nullptr, "Pa", 0.0, 1e5, false,
     "Herschel-Bulkley yield stress: below it the material holds its shape, heaps and sticks."},
    {"consistency", &Material::consistency, nullptr, "Pa*s^n", 0.0, 1e4, false,
     "Herschel-Bulkley consistency K: the flowing stress above the yield stress is K rate^n."},
    {"flowIndex", &Material::flowIndex, nullptr, "1", 0.1, 2.0, false,
     "Herschel-Bulkley flow index n: below 1 the material thins with shear, above 1 thickens."},
    {"shearModulus", &Material::shearModulus, nullptr, "Pa", 0.0, 1e6, false,
     "Stiffness below the yield stress; 0 is as stiff as the step allows."},
};

} // namespace

std::span<const MaterialField> materialFields() {
    return kFields;
}

void validate(const Material& m) {
    internal::checkName("material", m.name);
    for (const MaterialField& f : kFields) {
        // Compared in the field's own type: a bound such as 1e-4 is not a float, and the
        // float nearest to it (what a level or a tuning panel stores) must pass.
        const float value = m.*f.real;
        const auto lo = float(f.lo);
        const auto hi = float(f.hi);
        const bool ok =
            std::isfinite(value) && (f.openLow ? value > lo : value >= lo) && value <= hi;
        if (!ok) {
            std::ostringstream s;
            s << "material '" << m.name << "': " << f.name << " = " << internal::formatValue(value)
              << " is " << (std::isfinite(value) ? "out of range " : "not finite; expected ")
              << (f.openLow ? "(" : "[") << f.lo << ", " << f.hi << "] (unit: " << f.unit << ")";
            throw Error(s.str(),
                        std::isfinite(value) ? ErrorCode::OutOfRange : ErrorCode::BadArgument);
        }
    }
}

bool hasYield(const Material& m) {
    return m.yieldStress > 0.0f || m.consistency > 0.0f;
}

float particleArea(const Material& material, float depth) {
    return material.mass / (material.restDensity * depth);
}

float particleSpacing(const Material& material, float depth) {
    return std::sqrt(particleArea(material, depth));
}

} // namespace fluid
