// fluid — 2D SPH liquid for games.
#pragma once

#include <fluid/fields.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace fluid {

/// A liquid's physical parameters: the fields of the seed report's Table 4.1 plus surface tension.
///
/// Reading 3D quantities in a 2D world (read once here; every other comment refers back to it):
/// the world is a slab of fluid of depth `WorldDef::depth` (unit: m, default 0.1293 m, see
/// `kDefaultDepth`). A particle is a column of that slab: it carries the material's 3D `mass`
/// (kg) and covers an area `A = mass / (restDensity * depth)` (m^2) of the plane, so at rest the
/// 3D density of the slab is `restDensity`. Densities are therefore 3D (kg/m^3), computed with a
/// kernel normalised over the plane: `rho_i = sum_j (m_j / depth) W2(|x_i - x_j|, h)`.
/// Momentum, forces and energies use the 3D mass, so a body coupled to the fluid sees an areal
/// density of `restDensity * depth` kg/m^2 (129.3 kg/m^2 for water at the default depth).
/// Blobs are filled on a square lattice of spacing `sqrt(A)`. `kernelParticles` is the table's
/// count of particles inside the support circle; the default depth is the one at which water's
/// count is exactly 32 (`depth = m N / (rho0 pi h^2)`); yoghurt then reads 48.75 (the table's
/// 50 cannot hold for both presets at one depth: the table is a 3D tuning). Both presets get a
/// spacing of about 0.0100 m.
struct Material {
    /// Particle mass (unit: kg; range (0, 1e3]). Seed water: 0.013, yoghurt: 0.014.
    float mass = 0.013f;
    /// Rest ("ideal") density (unit: kg/m^3; range (0, 1e5]). Seed water: 1000, yoghurt: 1050.
    float restDensity = 1000.0f;
    /// Dynamic viscosity mu of the seed's eq. 2.6 (unit: Pa*s; range [0, 1e4]). Seed water: 3.5,
    /// yoghurt: 20.0 (tuned values from the seed, far above real water's 0.001). For a material
    /// with a yield stress it is the flow law's high-shear limit, added to K gamma_dot^n.
    float viscosity = 3.5f;
    /// Stiffness k of the seed's linear equation of state p = k (rho - rho0) (unit: J/kg, i.e.
    /// m^2/s^2: its square root is the sound speed; range (0, 1e8]). Seed water: 3.0, yoghurt: 5.0.
    /// Used by `EquationOfState::Linear`, and as the sound-speed floor sqrt(k) of `Tait`.
    float stiffness = 3.0f;
    /// Smoothing distance: the kernel's support radius h (unit: m; range [3e-3, 0.4], and 3 to 8
    /// particle spacings: `kMinSupportSpacings`). Seed water: 0.032, yoghurt: 0.04.
    float smoothingDistance = 0.032f;
    /// Particles inside the support circle that the material was tuned for (unit: count; range
    /// [4, 400]). Seed water: 32, yoghurt: 50. Informational: see the 2D reading above.
    float kernelParticles = 32.0f;
    /// Surface tension / cohesion coefficient gamma of [Akinci 2013] (unit: m^3/(kg s^2); range
    /// [0, 0.5]: above it a dam break gains energy; docs/levels.md, Corners). 0 disables it. Not in the seed's table; presets: water 0.1, yoghurt 0.1.
    /// With a yield stress, the position-based solver also holds the material's skin against
    /// another liquid with up to 6 times this between two of its particles there
    /// (docs/yield_stress.md, "Its skin against the water").
    float surfaceTension = 0.1f;
    /// Yield stress tau_y of the Herschel-Bulkley law tau = tau_y + K gamma_dot^n (unit: Pa; range
    /// [0, 1e5]). Below it the material does not flow: it holds a heap, a shape in zero gravity,
    /// and sticks to walls, deforming elastically (`shearModulus`); above it it flows. 0 with
    /// `consistency` 0 (the default): a Newtonian liquid, stepped exactly as without these
    /// fields. Water preset: 0; yoghurt: 400 (yoghurt as a player sees it at the preset's 1 cm
    /// spacing: a dollop heaps, a splash sticks to a wall, a rested 4 cm layer holds on a 23
    /// degree plank at `Quality::Game`; stirred yoghurt measures 5-30 Pa,
    /// docs/position_based.md). Position-based
    /// solver only: the explicit solver refuses a material with a yield stress or a consistency.
    /// The step stores no stress above G times a strain of 1 (G as `shearModulus` says: about
    /// 2,200 Pa for the yoghurt preset at the default settings, 540 Pa at `Quality::Game`): a
    /// stiffer material flows there, and stays as rigid inside as its own yield stress says.
    float yieldStress = 0.0f;
    /// Consistency K of the Herschel-Bulkley law (unit: Pa*s^n; range [0, 1e4]): the flowing
    /// stress above the yield stress is K gamma_dot^n, on top of the Newtonian `viscosity`
    /// (which is the law's high-shear limit), up to the stress the step stores (see
    /// `yieldStress`). Water: 0; yoghurt: 2 (measured 1-4 Pa*s^n).
    float consistency = 0.0f;
    /// Flow index n of the Herschel-Bulkley law (unit: 1; range [0.1, 2]): below 1 the material
    /// thins with shear, above 1 it thickens. Water: 1; yoghurt: 0.7 (measured 0.6-0.85).
    float flowIndex = 1.0f;
    /// Shear modulus G below the yield stress (unit: Pa; range [0, 1e6]): how far the material
    /// bends before it yields (a strain of yieldStress / G). The stress pass uses at most what
    /// its step can carry, rho0 (0.15 h / dt)^2 for a viscosity run of dt (about 2,200 Pa for
    /// the yoghurt preset at the default settings, 540 Pa at `Quality::Game`); 0 asks for that
    /// bound. The shear constraint (`PositionBasedDef::shearConstraint`) uses a stiffer one as
    /// it is, its sweeps' update scaled (0 asks for the same bound per sub-step). Only read
    /// when `yieldStress` or `consistency` is positive. Water: 200 (unused);
    /// yoghurt: 0. Stirred yoghurt's storage modulus is about 100-500 Pa, but at 200 Pa a
    /// stirred yoghurt wobbles like jelly after the spoon leaves (docs/position_based.md).
    float shearModulus = 200.0f;
    /// Display name (printable text for tools and error messages: no control characters,
    /// i.e. no byte below 0x20 and no 0x7f; UTF-8 allowed; `validate` refuses others).
    std::string name = "water";
};

/// The seed's water (Table 4.1, values unchanged). Thread rule: any thread.
Material water();
/// The seed's yoghurt exactly as Table 4.1 gives it: a Newtonian liquid of viscosity 20 Pa*s,
/// no yield stress or consistency, named "seed_yoghurt". The yoghurt the explicit solver steps
/// (it refuses `yoghurt()`), and the one to compare with the report. Thread rule: any thread.
Material seedYoghurt();
/// The seed's yoghurt (Table 4.1, values unchanged) with a Herschel-Bulkley flow law: yield
/// stress 400 Pa (thick yoghurt as a game shows it; the measured 5-30 Pa barely heaps at the
/// preset's spacing), consistency 2 Pa*s^n, flow index 0.7, shear modulus 0 (as stiff as the step
/// allows). Table 4.1's viscosity of 20 Pa*s stays as the law's high-shear limit. Thread rule:
/// any thread.
Material yoghurt();

/// True when `material` follows the Herschel-Bulkley law (a positive yield stress or
/// consistency) rather than the Newtonian one. Thread rule: any thread.
bool hasYield(const Material& material);

/// A number of `Material` (see `Field`).
using MaterialField = Field<Material>;

/// Every number of `Material`, in the order snapshots store them; `validate` checks each
/// against its range. Static storage. Any thread.
std::span<const MaterialField> materialFields();

/// Checks every field is finite and inside its documented range; throws `fluid::Error` naming
/// the field and its value, e.g. "material 'water': viscosity = -1 is out of range [0, 10000]
/// (unit: Pa*s)". A float field equal to its bound rounded to float (the smallest
/// smoothingDistance, 3e-3f) is inside. The fields that set the spacing are checked together
/// by `World::addMaterial`, which knows the depth. The name must be printable text ("material 'w\x1b':
/// the name holds a control character (byte 0x1b at offset 1); names are printable text").
/// Thread rule: any thread.
void validate(const Material& material);

/// Default slab depth (unit: m): the depth at which the water preset has exactly its table's
/// 32 kernel particles, 0.013 * 32 / (1000 * pi * 0.032^2) = 0.12931 m.
inline constexpr float kDefaultDepth = 0.12931339f;

/// The particle spacings a world steps (unit: m; the spacing is sqrt(mass / (restDensity
/// depth)), set by `Material::mass`, `Material::restDensity` and `WorldDef::depth` together).
/// `World::addMaterial` refuses a material outside them: finer costs the most per frame, coarser
/// lets the game preset's coarse correction gain energy (docs/levels.md, Corners).
inline constexpr float kMinSpacing = 1e-3f;
/// See `kMinSpacing` (unit: m).
inline constexpr float kMaxSpacing = 0.05f;
/// The kernel support a world steps, in particle spacings (unit: 1): `smoothingDistance` over
/// the spacing. Outside [3, 8] a dam break gains energy, and above 8 it also costs 2-3x the
/// presets' (water 3.2, yoghurt 3.9; docs/levels.md, Corners).
inline constexpr float kMinSupportSpacings = 3.0f;
/// See `kMinSupportSpacings` (unit: 1).
inline constexpr float kMaxSupportSpacings = 8.0f;

/// Area one particle of `material` covers in a slab of `depth` (unit: m^2): mass/(rho0 depth).
float particleArea(const Material& material, float depth);
/// Lattice spacing of `material` in a slab of `depth` (unit: m): sqrt(particleArea).
float particleSpacing(const Material& material, float depth);

} // namespace fluid
