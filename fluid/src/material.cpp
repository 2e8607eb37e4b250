// fluid — materials: the seed's Table 4.1 presets and validation.
#include <fluid/error.h>
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

Material yoghurt() {
    Material m;
    m.mass = 0.014f;
    m.restDensity = 1050.0f;
    m.viscosity = 20.0f;
    m.stiffness = 5.0f;
    m.smoothingDistance = 0.04f;
    m.kernelParticles = 50.0f;
    m.surfaceTension = 0.1f;
    m.yieldStress = 30.0f;
    m.consistency = 2.0f;
    m.flowIndex = 0.7f;
    m.shearModulus = 0.0f;
    m.name = "yoghurt";
    return m;
}

namespace {
void check(const Material& m, const char* field, float value, float lo, float hi, bool openLow,
           const char* unit) {
    const bool ok = std::isfinite(value) && (openLow ? value > lo : value >= lo) && value <= hi;
    if (!ok) {
        std::ostringstream s;
        s << "material '" << m.name << "': " << field << " = " << value << " is "
          << (std::isfinite(value) ? "out of range " : "not finite; expected ")
          << (openLow ? "(" : "[") << lo << ", " << hi << "] (unit: " << unit << ")";
        throw Error(s.str());
    }
}
} // namespace

void validate(const Material& m) {
    check(m, "mass", m.mass, 0.0f, 1e3f, true, "kg");
    check(m, "restDensity", m.restDensity, 0.0f, 1e5f, true, "kg/m^3");
    check(m, "viscosity", m.viscosity, 0.0f, 1e4f, false, "Pa*s");
    check(m, "stiffness", m.stiffness, 0.0f, 1e8f, true, "J/kg");
    check(m, "smoothingDistance", m.smoothingDistance, 1e-4f, 10.0f, false, "m");
    check(m, "kernelParticles", m.kernelParticles, 4.0f, 400.0f, false, "count");
    check(m, "surfaceTension", m.surfaceTension, 0.0f, 1e3f, false, "m^3/(kg s^2)");
    check(m, "yieldStress", m.yieldStress, 0.0f, 1e5f, false, "Pa");
    check(m, "consistency", m.consistency, 0.0f, 1e4f, false, "Pa*s^n");
    check(m, "flowIndex", m.flowIndex, 0.1f, 2.0f, false, "1");
    check(m, "shearModulus", m.shearModulus, 0.0f, 1e6f, false, "Pa");
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
