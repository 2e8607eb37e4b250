// fluid — the World API: materials, particles, handles, blobs, plugins.
#include "world_state.h"

#include <fluid/error.h>
#include <fluid/internal/checks.h>

#include <glm/common.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <new>
#include <sstream>

namespace fluid {

namespace {

std::string describe(ParticleHandle h) {
    std::ostringstream s;
    s << "{slot " << h.slot << ", generation " << h.generation << "}";
    return s.str();
}

using internal::finite;

void checkVec(const char* function, const char* what, glm::vec2 v) {
    if (!finite(v)) {
        std::ostringstream s;
        s << function << ": " << what << " = (" << v.x << ", " << v.y << ") is not finite";
        throw Error(s.str(), ErrorCode::BadArgument);
    }
}

// Throws unless `id` was made by the world tagged `tag` or by hand (tag 0): "<what> id <index>
// was made by another world (world <w>; this is world <tag>; ...)".
template <class Id> void checkTag(Id id, const char* what, uint32_t tag) {
    if (id.world != 0 && id.world != tag) {
        throw Error(std::string(what) + " id " + std::to_string(id.index) +
                        " was made by another world (world " + std::to_string(id.world) +
                        "; this is world " + std::to_string(tag) +
                        "; an id kept from the world a snapshot was saved from needs World::adopt)",
                    ErrorCode::StaleId);
    }
}

void checkFrameDt(const char* function, float frameDt) {
    if (!std::isfinite(frameDt) || !(frameDt > 0.0f) || frameDt > 1.0f) {
        std::ostringstream s;
        s << function << ": frameDt = " << frameDt
          << " s is out of range; expected a finite value in (0, 1] (typically 1/60)";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
}

// internal::checkRange with the settings' prefix by default.
template <class T>
void checkRange(const char* field, T value, T lo, T hi, const char* unit,
                const char* prefix = "WorldDef: ") {
    internal::checkRange<T>(prefix, field, value, lo, hi, unit);
}

// In the order snapshots store them (the struct's own order).
constexpr Field<PositionBasedDef> kPositionBasedFields[] = {
    {"substeps", nullptr, &PositionBasedDef::substeps, "count", 1, 12, false,
     "Position-based sub-steps per 1/60 s frame (more for longer frames); more hold the water "
     "denser and cost more."},
    {"iterations", nullptr, &PositionBasedDef::iterations, "count", 1, 32, false,
     "Density-constraint (Jacobi) iterations per sub-step."},
    {"viscosityInterval", nullptr, &PositionBasedDef::viscosityInterval, "count", 1, 64, false,
     "Sub-steps between viscosity and surface tension runs."},
    {"coarseCorrection", &PositionBasedDef::coarseCorrection, nullptr, "1", 0, 1, false,
     "Share of the coarse-grid density correction per sub-step; 0 is off "
     "(docs/position_based.md, \"Coarse correction\")."},
    {"vorticity", &PositionBasedDef::vorticity, nullptr, "1", 0, 1, false,
     "Vorticity confinement: gives back the swirl that damping takes; 0 is off."},
    {"shearConstraint", nullptr, &PositionBasedDef::shearConstraint, "switch", 0, 1, false,
     "Yield-stress materials: 1 steps them with the elastoplastic shear constraint (heaps come "
     "to rest), 0 with the stress pass."},
};

// In the order snapshots store them.
constexpr Field<WorldDef> kWorldFields[] = {
    {"depth", &WorldDef::depth, nullptr, "m", 1e-4, 1e3, false,
     "Slab depth that reads the materials' 3D mass and density in 2D (see Material)."},
    {"courant", &WorldDef::courant, nullptr, "1", 0.01, 1, false, "Explicit solver's CFL number."},
    {"maxSubsteps", nullptr, &WorldDef::maxSubsteps, "count", 1, 1000, false,
     "Explicit solver's sub-step cap per frame: it bounds the frame's cost (about 0.3 s for 400 "
     "particles at 1000)."},
    {"maxParticles", nullptr, &WorldDef::maxParticles, "count", 1, 67108864, false,
     "Most particles the world holds (blobs and emitters)."},
};

constexpr Field<EmitterDef> kEmitterFields[] = {
    {"speed", &EmitterDef::speed, nullptr, "m/s", 0.01, 100, false, "Exit speed."},
    {"width", &EmitterDef::width, nullptr, "m", 0, 100, false,
     "Nozzle width; 0 = one particle per row."},
    {"rate", &EmitterDef::rate, nullptr, "1/s", 0, 1e6, false,
     "Particles per second; 0 = closed. At most lanes x speed / spacing (the world says the "
     "limit)."},
    {"maxCount", nullptr, &EmitterDef::maxCount, "count", 0, 4294967295.0, false,
     "Most particles over the emitter's life; 0 = no limit."},
    {"lifetime", &EmitterDef::lifetime, nullptr, "s", 0, 1e6, false,
     "Lifetime of each emitted particle; 0 = forever."},
    {"jitter", &EmitterDef::jitter, nullptr, "1", 0, 0.5, false,
     "Random offset across the jet, in spacings."},
};

// Checks every field of `def` against its range: "<prefix><name> = <value> is out of range
// [lo, hi] (unit: ...)" (whole numbers printed whole). The tables have no open lower ends.
template <class Def>
void checkFields(const Def& def, std::span<const Field<Def>> fields, const std::string& prefix) {
    for (const Field<Def>& f : fields) {
        if (f.whole != nullptr) {
            internal::checkRange<uint32_t>(prefix, f.name, def.*f.whole, uint32_t(f.lo),
                                           uint32_t(f.hi), f.unit);
        } else {
            internal::checkRange<float>(prefix, f.name, def.*f.real, float(f.lo), float(f.hi),
                                        f.unit);
        }
    }
}

void validatePositionBased(const PositionBasedDef& pb, const char* prefix) {
    checkFields<PositionBasedDef>(pb, kPositionBasedFields, prefix);
    // One sweep holds only with the coarse correction: without it a dam break compresses and
    // rebounds with more energy than it started with (docs/levels.md, Corners).
    if (pb.iterations < 2 && !(pb.coarseCorrection > 0.0f)) {
        std::ostringstream s;
        s << prefix << "iterations = " << pb.iterations
          << " needs the coarse correction, but coarseCorrection = " << pb.coarseCorrection
          << "; use 2 or more iterations, or a coarseCorrection above 0 (the game preset: 1 "
             "iteration, 0.4)";
        throw Error(s.str(), ErrorCode::BadArgument);
    }
}

void validate(const WorldDef& def) {
    if (!(def.soundSpeed == 0.0f || (def.soundSpeed >= 0.1f && def.soundSpeed <= 1e4f))) {
        std::ostringstream s;
        s << "WorldDef: soundSpeed = " << def.soundSpeed
          << " is out of range: 0 (derive from the scene) or [0.1, 10000] (unit: m/s)";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
    checkFields<WorldDef>(def, kWorldFields, "WorldDef: ");
    validatePositionBased(def.positionBased, "WorldDef: positionBased.");
    if (def.tasks.enqueue == nullptr) {
        checkRange<uint32_t>("workerCount", def.workerCount, 1, 256, "count");
    } else {
        if (def.tasks.finish == nullptr) {
            throw Error("WorldDef: tasks.enqueue is set but tasks.finish is null",
                        ErrorCode::BadArgument);
        }
        checkRange<uint32_t>("tasks.workerCount", def.tasks.workerCount, 1, 256, "count");
    }
}

void checkLifetime(const char* function, float seconds) {
    checkRange("lifetime", seconds, 0.0f, 1e6f, "s", function);
}

} // namespace

namespace detail {

namespace {
// The next world's tag. Tags are never reused within a process, so a handle kept from a
// destroyed world (a level restarted) is refused by every later world.
std::atomic<uint32_t> g_nextTag{1};
} // namespace

WorldTag::WorldTag() {
    uint32_t tag = g_nextTag.load(std::memory_order_relaxed);
    do {
        if (tag == UINT32_MAX) {
            throw Error("World: the process has made 4294967294 worlds, every world tag is used "
                        "(tags are never reused, so that an old world's handles stay refused)",
                        ErrorCode::Full);
        }
    } while (!g_nextTag.compare_exchange_weak(tag, tag + 1, std::memory_order_relaxed));
    m_value = tag;
}

size_t WorldState::finestMaterial() const {
    size_t finest = 0;
    for (size_t k = 1; k < materials.size(); ++k) {
        if (particleSpacing(materials[k], def.depth) <
            particleSpacing(materials[finest], def.depth)) {
            finest = k;
        }
    }
    return finest;
}

float WorldState::positionLimit() const {
    if (materials.empty()) {
        return 0.0f;
    }
    const float finest = particleSpacing(materials[finestMaterial()], def.depth);
    return std::min(kPositionSpacings * finest, kMaxPositionLimit);
}

void WorldState::checkInRange(const char* function, const char* what, glm::vec2 x) const {
    const float limit = positionLimit();
    if (std::fabs(x.x) <= limit && std::fabs(x.y) <= limit) {
        return;
    }
    std::ostringstream text;
    text << function << ": " << what << " = (" << x.x << ", " << x.y
         << ") is outside the position range [" << -limit << ", " << limit << "] (unit: m; ";
    if (materials.empty()) {
        text << "the world has no material yet)";
    } else {
        const size_t finest = finestMaterial();
        text << "2^18 spacings of the finest material, '" << materials[finest].name << "' at "
             << particleSpacing(materials[finest], def.depth)
             << " m; docs/gameplay.md, Far from the origin)";
    }
    throw Error(text.str(), ErrorCode::OutOfRange);
}

std::optional<uint32_t> WorldState::findIndex(ParticleHandle handle) const {
    if (handle.isNull() || handle.world != tag.value() || handle.slot >= slotGeneration.size() ||
        slotGeneration[handle.slot] != handle.generation || slotIndex[handle.slot] == UINT32_MAX) {
        return std::nullopt;
    }
    return slotIndex[handle.slot];
}

uint32_t WorldState::checkedIndex(ParticleHandle handle, const char* function) const {
    if (handle.isNull()) {
        throw Error(std::string(function) + ": null particle handle", ErrorCode::StaleId);
    }
    if (handle.world != tag.value()) {
        throw Error(std::string(function) + ": particle handle " + describe(handle) +
                        " belongs to another world (world " + std::to_string(handle.world) +
                        "; this is world " + std::to_string(tag.value()) +
                        "; a handle saved with a snapshot needs World::adopt)",
                    ErrorCode::StaleId);
    }
    const std::optional<uint32_t> index = findIndex(handle);
    if (!index) {
        throw Error(std::string(function) + ": stale particle handle " + describe(handle) +
                        ": that particle was removed",
                    ErrorCode::StaleId);
    }
    return *index;
}

void WorldState::reserveParticles(size_t count) {
    const auto grow = [count](auto& channel) {
        if (channel.capacity() < count) {
            channel.reserve(std::max(count, 2 * channel.capacity()));
        }
    };
    Particles& p = particles;
    for (std::vector<float>* channel : p.keptFloats()) {
        grow(*channel);
    }
    grow(p.material);
    grow(p.slot);
    grow(p.expiry);
    for (std::vector<float>* channel : {&p.lastX, &p.lastY}) {
        if (!channel->empty()) {
            grow(*channel);
        }
    }
    if (!p.colour.empty()) {
        grow(p.colour);
    }
    grow(slotIndex);
    grow(slotGeneration);
}

ParticleHandle WorldState::append(glm::vec2 x, glm::vec2 v, uint16_t material, double expiry,
                                  float structure) {
    // Room first: a bad_alloc then leaves the world as it was.
    reserveParticles(size_t(particles.size()) + 1);
    uint32_t slot = 0;
    if (!freeSlots.empty()) {
        slot = freeSlots.back();
        freeSlots.pop_back();
    } else {
        slot = static_cast<uint32_t>(slotIndex.size());
        slotIndex.push_back(UINT32_MAX);
        slotGeneration.push_back(1);
    }
    Particles& p = particles;
    slotIndex[slot] = p.size();
    p.px.push_back(x.x);
    p.py.push_back(x.y);
    p.vx.push_back(v.x);
    p.vy.push_back(v.y);
    p.density.push_back(0.0f);
    p.pressure.push_back(0.0f);
    p.sxx.push_back(0.0f);
    p.sxy.push_back(0.0f);
    p.structure.push_back(hasYield(materials[material]) ? structure : 0.0f);
    p.kx.push_back(0.0f);
    p.ky.push_back(0.0f);
    p.material.push_back(material);
    p.slot.push_back(slot);
    p.expiry.push_back(expiry);
    if (interpolate) { // new particles do not streak: previous = current
        p.lastX.push_back(x.x);
        p.lastY.push_back(x.y);
    }
    if (!p.colour.empty()) {
        p.colour.push_back(0);
    }
    return handleOf(slot);
}

void WorldState::releaseSlot(uint32_t slot) {
    leaveSlot(slot);
    slotIndex[slot] = UINT32_MAX;
    // Generation 0 is the null handle's: skip it when a slot's counter wraps.
    slotGeneration[slot] = slotGeneration[slot] + 1 == 0 ? 1 : slotGeneration[slot] + 1;
    freeSlots.push_back(slot);
}

void WorldState::removeAt(uint32_t index) {
    Particles& p = particles;
    const uint32_t last = p.size() - 1;
    releaseSlot(p.slot[index]);
    if (index != last) {
        for (std::vector<float>* channel : p.keptFloats()) {
            (*channel)[index] = (*channel)[last];
        }
        p.material[index] = p.material[last];
        p.slot[index] = p.slot[last];
        p.expiry[index] = p.expiry[last];
        for (std::vector<float>* channel : {&p.lastX, &p.lastY}) {
            if (!channel->empty()) {
                (*channel)[index] = (*channel)[last];
            }
        }
        if (!p.colour.empty()) {
            p.colour[index] = p.colour[last];
        }
        slotIndex[p.slot[index]] = index;
    }
    for (std::vector<float>* channel : {&p.lastX, &p.lastY}) {
        if (!channel->empty()) {
            channel->pop_back();
        }
    }
    if (!p.colour.empty()) {
        p.colour.pop_back();
    }
    for (std::vector<float>* channel : p.keptFloats()) {
        channel->pop_back();
    }
    p.material.pop_back();
    p.slot.pop_back();
    p.expiry.pop_back();
}

WorldState& stateOf(World& world) {
    return *world.m_state;
}

} // namespace detail

World::World(const WorldDef& def) : m_state(std::make_unique<detail::WorldState>()) {
    validate(def);
    m_state->def = def;
    if (def.tasks.enqueue != nullptr) {
        m_state->tasks = def.tasks;
    } else if (def.workerCount > 1) {
        m_state->pool = std::make_unique<ThreadPool>(def.workerCount);
        m_state->tasks = m_state->pool->hook();
    }
}

namespace {

// A world destroyed or overwritten from inside its own step (a plugin's hook deleting the world
// that runs it): the step would go on in freed memory. Neither can refuse (no exception leaves
// a destructor or a noexcept move), so the process stops with the rule, not a crash elsewhere.
void stopIfStepping(const detail::WorldState* s, const char* function) {
    if (s != nullptr && s->stepping) {
        std::fprintf(stderr,
                     "fluid: %s called during the world's own World::step (from a plugin's hook "
                     "or a task): a world is destroyed or replaced only between its steps\n",
                     function);
        std::abort();
    }
}

} // namespace

World::~World() {
    stopIfStepping(m_state.get(), "World::~World");
}
World::World(World&& other) noexcept : m_state(std::move(other.m_state)) {
    stopIfStepping(m_state.get(), "World::World(World&&)");
}
World& World::operator=(World&& other) noexcept {
    stopIfStepping(m_state.get(), "World::operator=(World&&)");
    stopIfStepping(other.m_state.get(), "World::operator=(World&&)");
    m_state = std::move(other.m_state);
    return *this;
}

namespace detail {

void WorldState::checkIdle(const char* function) const {
    if (stepping) {
        throw Error(std::string(function) +
                        ": called during the world's own step (from a plugin's hook or a task); a "
                        "world is changed, saved or stepped only between its steps",
                    ErrorCode::WrongState);
    }
}

} // namespace detail

namespace {
// The explicit solver steps Newtonian materials only.
void checkSolverTakes(const WorldDef& def, const Material& material, const char* function) {
    if (def.solver == Solver::Explicit && hasYield(material)) {
        std::ostringstream s;
        s << function << ": material '" << material.name << "' has a Herschel-Bulkley flow law "
          << "(yieldStress = " << material.yieldStress
          << " Pa, consistency = " << material.consistency
          << " Pa*s^n), which the explicit solver does not step; use Solver::PositionBased, "
             "or set yieldStress and consistency to 0";
        throw Error(s.str(), ErrorCode::BadArgument);
    }
}

// The settings that only make sense together: the spacing mass, rest density and depth give,
// and the smoothing distance in those spacings (kMinSpacing, kMinSupportSpacings).
void checkSpacing(const WorldDef& def, const Material& material, const char* function) {
    const double spacing =
        std::sqrt(double(material.mass) / (double(material.restDensity) * double(def.depth)));
    if (!(spacing >= double(kMinSpacing) * (1.0 - 1e-6) &&
          spacing <= double(kMaxSpacing) * (1.0 + 1e-6))) {
        std::ostringstream s;
        s << function << ": material '" << material.name << "': mass = " << material.mass
          << " kg, restDensity = " << material.restDensity << " kg/m^3 and depth = " << def.depth
          << " m give a particle spacing of sqrt(mass / (restDensity depth)) = " << spacing
          << " m; expected [" << kMinSpacing << ", " << kMaxSpacing << "] m";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
    const double support = double(material.smoothingDistance) / spacing;
    if (!(support >= double(kMinSupportSpacings) * (1.0 - 1e-6) &&
          support <= double(kMaxSupportSpacings) * (1.0 + 1e-6))) {
        std::ostringstream s;
        s << function << ": material '" << material.name
          << "': smoothingDistance = " << material.smoothingDistance << " m is " << support
          << " particle spacings (" << spacing << " m, from mass, restDensity and depth); expected "
          << kMinSupportSpacings << " to " << kMaxSupportSpacings << " spacings";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
}
} // namespace

std::span<const Field<PositionBasedDef>> positionBasedFields() {
    return kPositionBasedFields;
}

std::span<const Field<WorldDef>> worldFields() {
    return kWorldFields;
}

std::span<const Field<EmitterDef>> emitterFields() {
    return kEmitterFields;
}

MaterialId World::addMaterial(const Material& material) {
    m_state->changing("World::addMaterial");
    validate(material);
    checkSolverTakes(m_state->def, material, "World::addMaterial");
    checkSpacing(m_state->def, material, "World::addMaterial");
    if (m_state->materials.size() >= 65535) {
        throw Error("World::addMaterial: the world already has 65535 materials", ErrorCode::Full);
    }
    m_state->materials.push_back(material);
    m_state->sensorReadings.assign(m_state->sensors.size() * m_state->materials.size(), {});
    return MaterialId{static_cast<uint16_t>(m_state->materials.size() - 1), m_state->tag.value()};
}

void World::setMaterial(MaterialId id, const Material& material) {
    m_state->changing("World::setMaterial");
    (void)this->material(id);
    validate(material);
    checkSolverTakes(m_state->def, material, "World::setMaterial");
    checkSpacing(m_state->def, material, "World::setMaterial");
    // The material's spacing sets its emitters' lanes and rate limit: check them again, and
    // keep the old material if one no longer fits.
    const Material old = m_state->materials[id.index];
    m_state->materials[id.index] = material;
    try {
        for (const detail::EmitterState& e : m_state->emitters) {
            if (e.def.material == id) {
                validateEmitter(e.def, "World::setMaterial");
            }
        }
    } catch (...) {
        m_state->materials[id.index] = old;
        throw;
    }
    // A material that no longer yields drops its stress: only yielding worlds sort and step
    // the stress channels, and they must then hold zeros.
    if (!hasYield(material)) {
        detail::Particles& p = m_state->particles;
        for (uint32_t i = 0; i < p.size(); ++i) {
            if (p.material[i] == id.index) {
                p.sxx[i] = 0.0f;
                p.sxy[i] = 0.0f;
                p.structure[i] = 0.0f;
            }
        }
    }
}

const Material& World::material(MaterialId id) const {
    checkTag(id, "material", m_state->tag.value());
    if (id.index >= m_state->materials.size()) {
        throw Error("unknown material id " + std::to_string(id.index) + "; the world has " +
                        std::to_string(m_state->materials.size()) + " materials",
                    ErrorCode::StaleId);
    }
    return m_state->materials[id.index];
}

uint32_t World::materialCount() const {
    return static_cast<uint32_t>(m_state->materials.size());
}

ParticleHandle World::addParticle(glm::vec2 position, glm::vec2 velocity, MaterialId materialId) {
    m_state->changing("World::addParticle");
    checkVec("World::addParticle", "position", position);
    checkVec("World::addParticle", "velocity", velocity);
    (void)material(materialId);
    detail::WorldState& s = *m_state;
    s.checkInRange("World::addParticle", "position", position);
    if (s.particles.size() >= s.def.maxParticles) {
        throw Error("World::addParticle: particle cap exceeded: the world holds maxParticles = " +
                        std::to_string(s.def.maxParticles) + " particles",
                    ErrorCode::Full);
    }
    return s.append(position, velocity, materialId.index, std::numeric_limits<double>::infinity());
}

uint32_t World::spawnBlob(const BlobDef& blob, uint32_t* insideSolids) {
    m_state->changing("World::spawnBlob");
    const Material& mat = material(blob.material);
    checkVec("spawnBlob", "velocity", blob.velocity);
    checkLifetime("spawnBlob: ", blob.lifetime);
    checkRange("structure", blob.structure, 0.0f, 1.0f, "1", "spawnBlob: ");
    checkRange("latticeAngle", blob.latticeAngle, -6.2832f, 6.2832f, "rad", "spawnBlob: ");
    const Shape& shape = blob.shape;
    validate(shape, "spawnBlob");
    glm::vec2 lo{}, hi{};
    bounds(shape, lo, hi);
    m_state->checkInRange("spawnBlob", "the shape's lower corner", lo);
    m_state->checkInRange("spawnBlob", "the shape's upper corner", hi);
    const float spacing = particleSpacing(mat, m_state->def.depth);
    const double cols = std::floor(double(hi.x - lo.x) / spacing);
    const double rows = std::floor(double(hi.y - lo.y) / spacing);
    if (cols < 1.0 || rows < 1.0) {
        return 0; // thinner than one spacing: no lattice point fits
    }
    if (cols * rows > double(m_state->def.maxParticles)) {
        std::ostringstream s;
        s << "spawnBlob: particle cap exceeded: the blob needs about " << cols * rows
          << " particles; maxParticles = " << m_state->def.maxParticles;
        throw Error(s.str(), ErrorCode::Full);
    }
    try {
        return placeBlob(blob, lo, hi, spacing, cols, rows, insideSolids);
    } catch (const std::bad_alloc&) {
        std::ostringstream text;
        text << "spawnBlob: memory ran out making room for the blob's about "
             << uint64_t(cols * rows) << " particles beside the world's "
             << m_state->particles.size()
             << "; make the blob smaller or lower WorldDef::maxParticles";
        std::throw_with_nested(
            Error(text.str(), ErrorCode::OutOfMemory)); // the std::bad_alloc rides along, nested
    }
}

namespace {

// A circle of radius `radius` filled in rings a spacing apart, from half a spacing inside its
// outline inwards, each with the whole number of points nearest its length over the spacing
// (each point then stands for about a spacing squared, as on the lattice), every second ring
// turned half a step against the one outside it; one point at the centre when the disc the
// rings leave there has at least half a spacing squared of area. Rings start at `angle` (rad).
// A yield-stress paste keeps the outline it starts with: on the lattice a circle's outline is
// a staircase a spacing high, which the paste holds as notches (docs/yield_stress.md, "A
// round outline").
void ringFill(glm::vec2 center, float radius, float spacing, float angle,
              std::vector<glm::vec2>& points) {
    constexpr double kTwoPi = 6.283185307179586;
    const double s = spacing;
    double inner = radius; // radius of the disc the rings leave
    for (int k = 0;; ++k) {
        const double r = double(radius) - s * (double(k) + 0.5);
        if (r < 0.5 * s) {
            break;
        }
        const auto count = std::max<long>(1, std::lround(kTwoPi * r / s));
        const double phase = double(angle) + (k % 2 == 1 ? 0.5 * kTwoPi / double(count) : 0.0);
        for (long j = 0; j < count; ++j) {
            const double a = phase + kTwoPi * double(j) / double(count);
            points.emplace_back(center.x + float(r * std::cos(a)),
                                center.y + float(r * std::sin(a)));
        }
        inner = r - 0.5 * s;
    }
    if (0.5 * kTwoPi * inner * inner >= 0.5 * s * s) {
        points.push_back(center);
    }
}

} // namespace

uint32_t World::placeBlob(const BlobDef& blob, glm::vec2 lo, glm::vec2 hi, float spacing,
                          double cols, double rows, uint32_t* insideSolids) {
    const Shape& shape = blob.shape;
    // Lattice points at cell centres, spacing apart, centred in the shape's bounding box.
    const auto nx = static_cast<uint32_t>(cols);
    const auto ny = static_cast<uint32_t>(rows);
    const glm::vec2 origin =
        0.5f * (lo + hi) - 0.5f * spacing * glm::vec2(float(nx) - 1.0f, float(ny) - 1.0f);
    std::vector<glm::vec2> points;
    if (shape.type == ShapeType::Circle && material(blob.material).yieldStress > 0.0f) {
        ringFill(shape.center, shape.radius, spacing, blob.latticeAngle, points);
    } else if (blob.latticeAngle == 0.0f) {
        for (uint32_t j = 0; j < ny; ++j) {
            for (uint32_t i = 0; i < nx; ++i) {
                const glm::vec2 p = origin + spacing * glm::vec2(float(i), float(j));
                // Every lattice point of a rectangle's bounding box is inside it.
                if (shape.type == ShapeType::Rectangle || contains(shape, p)) {
                    points.push_back(p);
                }
            }
        }
    } else {
        // Rows along (cos a, sin a): the lattice at cell centres, centred in the shape's
        // bounding box in the turned frame, as the unturned one is in its box (a turned
        // rectangle along its rows holds the same rows and columns as the unturned one).
        const glm::vec2 along{std::cos(blob.latticeAngle), std::sin(blob.latticeAngle)};
        const glm::vec2 across{-along.y, along.x};
        glm::vec2 turnedLo{INFINITY, INFINITY}, turnedHi{-INFINITY, -INFINITY};
        const auto extend = [&](glm::vec2 p, float r) {
            const glm::vec2 q{p.x * along.x + p.y * along.y, p.x * across.x + p.y * across.y};
            turnedLo = glm::min(turnedLo, q - r);
            turnedHi = glm::max(turnedHi, q + r);
        };
        switch (shape.type) {
        case ShapeType::Rectangle:
            for (const glm::vec2 corner : {glm::vec2{-1.0f, -1.0f}, glm::vec2{1.0f, -1.0f},
                                           glm::vec2{1.0f, 1.0f}, glm::vec2{-1.0f, 1.0f}}) {
                extend(shape.center + corner * shape.halfExtents, 0.0f);
            }
            break;
        case ShapeType::Circle:
            extend(shape.center, shape.radius);
            break;
        case ShapeType::Polygon:
            for (const glm::vec2 v : shape.vertices) {
                extend(v, 0.0f);
            }
            break;
        }
        const glm::vec2 extent = turnedHi - turnedLo;
        const auto ni = static_cast<int32_t>(std::floor(extent.x / spacing));
        const auto nj = static_cast<int32_t>(std::floor(extent.y / spacing));
        const glm::vec2 first =
            0.5f * (turnedLo + turnedHi) - 0.5f * spacing * glm::vec2(float(ni - 1), float(nj - 1));
        for (int32_t j = 0; j < nj; ++j) {
            for (int32_t i = 0; i < ni; ++i) {
                const float u = first.x + spacing * float(i), v = first.y + spacing * float(j);
                const glm::vec2 p = u * along + v * across;
                if (contains(shape, p)) {
                    points.push_back(p);
                }
            }
        }
    }
    // Lattice points inside a boundary's solid (or outside its container) would be thrown out
    // at the first step, violently: they are left out.
    const std::size_t before = points.size();
    std::erase_if(points, [&](glm::vec2 p) {
        for (const auto& boundary : m_state->boundaries) {
            if (boundary->contains(p)) {
                return true;
            }
        }
        return false;
    });
    if (insideSolids != nullptr) {
        *insideSolids = static_cast<uint32_t>(before - points.size());
    }
    if (m_state->particles.size() + points.size() > m_state->def.maxParticles) {
        throw Error("spawnBlob: particle cap exceeded: " + std::to_string(points.size()) +
                        " more particles would pass maxParticles = " +
                        std::to_string(m_state->def.maxParticles),
                    ErrorCode::Full);
    }
    const double expiry = detail::expiryTime(m_state->time, blob.lifetime);
    // The blob's group: the one named, or a new one (made only once the blob fits).
    uint32_t group = detail::WorldState::kNoGroup;
    if (!blob.group.isNull()) {
        group = detail::checkedGroup(*m_state, blob.group, "spawnBlob");
    }
    m_state->reserveParticles(size_t(m_state->particles.size()) + points.size());
    if (group == detail::WorldState::kNoGroup) {
        group = m_state->newGroup(0, 0);
    }
    const uint32_t first = m_state->particles.size();
    for (glm::vec2 p : points) {
        m_state->append(p, blob.velocity, blob.material.index, expiry, blob.structure);
    }
    for (uint32_t i = first; i < m_state->particles.size(); ++i) {
        m_state->joinGroup(i, group, true);
    }
    return static_cast<uint32_t>(points.size());
}

void World::removeParticle(ParticleHandle handle) {
    m_state->changing("World::removeParticle");
    m_state->removeAt(m_state->checkedIndex(handle, "World::removeParticle"));
}

ParticleHandle World::adopt(ParticleHandle handle) const {
    handle.world = handle.isNull() ? 0 : m_state->tag.value();
    return handle;
}

MaterialId World::adopt(MaterialId id) const {
    return MaterialId{id.index, m_state->tag.value()};
}

EmitterId World::adopt(EmitterId id) const {
    return EmitterId{id.index, m_state->tag.value()};
}

DrainId World::adopt(DrainId id) const {
    return DrainId{id.index, m_state->tag.value()};
}

SensorId World::adopt(SensorId id) const {
    return SensorId{id.index, m_state->tag.value()};
}

bool World::isValid(ParticleHandle handle) const {
    return indexOf(handle).has_value();
}

std::optional<uint32_t> World::indexOf(ParticleHandle handle) const {
    return m_state->findIndex(handle);
}

ParticleHandle World::handleAt(uint32_t index) const {
    if (index >= particleCount()) {
        throw Error("World::handleAt: index " + std::to_string(index) +
                        " is out of range; the world has " + std::to_string(particleCount()) +
                        " particles",
                    ErrorCode::OutOfRange);
    }
    const uint32_t slot = m_state->particles.slot[index];
    return m_state->handleOf(slot);
}

glm::vec2 World::position(ParticleHandle handle) const {
    const uint32_t i = m_state->checkedIndex(handle, "World::position");
    return {m_state->particles.px[i], m_state->particles.py[i]};
}

glm::vec2 World::velocity(ParticleHandle handle) const {
    const uint32_t i = m_state->checkedIndex(handle, "World::velocity");
    return {m_state->particles.vx[i], m_state->particles.vy[i]};
}

void World::setVelocity(ParticleHandle handle, glm::vec2 velocity) {
    m_state->changing("World::setVelocity");
    const uint32_t i = m_state->checkedIndex(handle, "World::setVelocity");
    checkVec("World::setVelocity", "velocity", velocity);
    m_state->particles.vx[i] = velocity.x;
    m_state->particles.vy[i] = velocity.y;
    m_state->particles.kx[i] = 0.0f; // the host's velocity replaces a pending change too
    m_state->particles.ky[i] = 0.0f;
}

ForcePlugin& World::addForce(std::unique_ptr<ForcePlugin> plugin) {
    m_state->changing("World::addForce");
    if (!plugin) {
        throw Error("World::addForce: null plugin", ErrorCode::BadArgument);
    }
    m_state->forces.push_back(std::move(plugin));
    return *m_state->forces.back();
}

BoundaryPlugin& World::addBoundary(std::unique_ptr<BoundaryPlugin> plugin) {
    m_state->changing("World::addBoundary");
    if (!plugin) {
        throw Error("World::addBoundary: null plugin", ErrorCode::BadArgument);
    }
    m_state->boundaries.push_back(std::move(plugin));
    return *m_state->boundaries.back();
}

std::span<const std::unique_ptr<ForcePlugin>> World::forces() const {
    return m_state->forces;
}
std::span<const std::unique_ptr<BoundaryPlugin>> World::boundaries() const {
    return m_state->boundaries;
}

bool World::stepping() const {
    return m_state->stepping;
}

void World::step(float frameDt) {
    m_state->changing("World::step");
    checkFrameDt("World::step", frameDt);
    if (m_state->materials.empty()) {
        throw Error("World::step: the world has no material; call addMaterial first",
                    ErrorCode::WrongState);
    }
    // A plugin that carries another engine's bodies has its host step the world with them.
    for (std::size_t k = 0; k < m_state->boundaries.size(); ++k) {
        const char* host = m_state->boundaries[k]->steppedBy();
        if (host != nullptr) {
            throw Error(
                "World::step: boundary plugin " + std::to_string(k) + " (" +
                    internal::quoted(m_state->boundaries[k]->type()) +
                    ") carries another engine's bodies: step the world with " + host +
                    ", which moves them with it; a bare World::step would leave them behind",
                ErrorCode::WrongState);
        }
    }
    detail::WorldState& s = *m_state;
    // The position-based solver steps in sub-steps of a fixed length, 1/60 s over the setting's
    // count, whatever the frame: the frame simulates the whole sub-steps nearest to the time
    // due (what is carried plus the frame) and carries the difference, positive or negative, to
    // the next frame, so the world's time never strays more than half a sub-step from the sum
    // of the frames. A correction turns into velocity over its sub-step, so a shorter sub-step
    // would turn the same residual compression into a faster motion (docs/position_based.md,
    // "Frame length").
    float simulated = frameDt;
    double carryAfter = 0.0; // stored once the step went through: a throwing step keeps the old
    if (s.def.solver == Solver::PositionBased) {
        const double h = detail::substepLength(s.def.positionBased.substeps);
        const double due = s.carry + double(frameDt);
        const uint32_t count = detail::dueSubsteps(due, h);
        if (count == 0) {
            s.carry = due;
            s.removed.clear();
            detail::clearContacts(s);
            s.profile = Profile{};
            s.profile.particles = s.particles.size();
            return;
        }
        s.plannedSubsteps = count;
        simulated = float(double(count) * h);
        carryAfter = due - double(count) * h; // in [-h / 2, h / 2)
    }
    frameDt = simulated;
    // Emitters add this frame's particles, the solver moves everything, then drains, lifetimes
    // and sensors see where the particles ended (events for the host to read).
    s.removed.clear();
    // A plugin's prepare hook may throw (a bad shape, a user plugin's own check) after the
    // emitters ran: keep what emission changes, so that the world can be put back.
    const detail::EmissionUndo undo(s);
    struct Stepping { // s.stepping while the plugins' hooks and the tasks run
        detail::WorldState& state;
        explicit Stepping(detail::WorldState& w) : state(w) { state.stepping = true; }
        ~Stepping() { state.stepping = false; }
        Stepping(const Stepping&) = delete;
        Stepping& operator=(const Stepping&) = delete;
    };
    uint32_t blocked = 0, skipped = 0;
    uint32_t emitted = 0;
    try {
        const Stepping stepping(s);
        emitted = detail::emitParticles(s, frameDt, blocked, skipped);
        if (s.interpolate && s.interpolateSteps && s.def.solver == Solver::Explicit &&
            frameDt > 0.0f) {
            // Interpolation::Step (groups.h): where the particles start the frame; its sorts
            // carry them along (the position-based solver takes them in its first sub-step).
            detail::resetPrevious(s);
            s.permuteLast = true;
        }
        switch (s.def.solver) {
        case Solver::PositionBased:
            detail::stepPositionBased(s, frameDt);
            break;
        case Solver::Explicit:
            detail::stepExplicit(s, frameDt);
            break;
        }
    } catch (...) {
        undo.restore(s);
        s.plannedSubsteps = 0;
        throw;
    }
    s.carry = carryAfter;
    s.permuteLast = false;
    if (s.interpolate && !s.interpolateSteps && s.def.solver == Solver::Explicit) {
        detail::resetPrevious(s); // whole frames: nothing to draw between sub-steps
    }
    detail::mixColours(s, double(simulated));
    s.profile.removed = detail::finishGameplay(s);
    s.profile.emitted = emitted;
    s.profile.emitBlocked = blocked;
    s.profile.emitSkipped = skipped;
    s.profile.particles = s.particles.size();
}

void World::setLifetime(ParticleHandle handle, float seconds) {
    m_state->changing("World::setLifetime");
    const uint32_t i = m_state->checkedIndex(handle, "World::setLifetime");
    checkLifetime("World::setLifetime: ", seconds);
    m_state->particles.expiry[i] = detail::expiryTime(m_state->time, seconds);
}

float World::lifetime(ParticleHandle handle) const {
    const uint32_t i = m_state->checkedIndex(handle, "World::lifetime");
    return float(m_state->particles.expiry[i] - m_state->time);
}

namespace {

// Particles across one emitter row: far beyond any nozzle a game draws, and small enough that
// a row always fits the counters.
constexpr uint32_t kMaxEmitterLanes = 10000;

template <class Id>
uint32_t checkedId(Id id, size_t count, const char* function, const char* what, uint32_t tag) {
    checkTag(id, (std::string(function) + ": " + what).c_str(), tag);
    if (id.index >= count) {
        throw Error(std::string(function) + ": unknown " + what + " id " +
                        std::to_string(id.index) + "; the world has " + std::to_string(count) +
                        " " + what + "s",
                    ErrorCode::StaleId);
    }
    return id.index;
}

} // namespace

void World::validateEmitter(const EmitterDef& def, const char* function) const {
    const std::string prefix = std::string(function) + ": ";
    checkVec(function, "position", def.position);
    checkVec(function, "direction", def.direction);
    if (detail::unitDirection(def.direction) == glm::vec2(0.0f, 0.0f)) {
        std::ostringstream s;
        s << prefix << "direction = (" << def.direction.x << ", " << def.direction.y
          << ") has no direction; expected a non-zero vector";
        throw Error(s.str(), ErrorCode::BadArgument);
    }
    checkFields<EmitterDef>(def, kEmitterFields, prefix);
    const Material& mat = material(def.material);
    m_state->checkInRange(function, "position", def.position);
    const float spacing = particleSpacing(mat, m_state->def.depth);
    const double lanes = detail::emitterLanes(def.width, spacing);
    if (!(lanes <= double(kMaxEmitterLanes))) {
        std::ostringstream s;
        s << prefix << "width = " << def.width << " m is " << lanes << " lanes at " << spacing
          << " m spacing; at most " << kMaxEmitterLanes;
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
    // Rows closer than one spacing would overlap: the jet would start compressed.
    const auto limit = float(lanes * def.speed / spacing);
    if (def.rate > limit * 1.0001f) {
        std::ostringstream s;
        s << prefix << "rate = " << def.rate << " particles/s overlaps: a nozzle " << def.width
          << " m wide (" << lanes << " lanes at " << spacing << " m spacing) at speed " << def.speed
          << " m/s emits at most " << limit
          << " particles/s; lower the rate, or widen or speed up the jet";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
}

EmitterId World::addEmitter(const EmitterDef& def) {
    m_state->changing("World::addEmitter");
    validateEmitter(def, "World::addEmitter");
    detail::EmitterState e;
    e.def = def;
    e.random = def.seed;
    m_state->emitters.push_back(e);
    m_state->emitterGroup.resize(m_state->emitters.size() - 1, detail::WorldState::kNoGroup);
    m_state->emitterGroup.push_back(m_state->newGroup(0, 0));
    return EmitterId{static_cast<uint32_t>(m_state->emitters.size() - 1), m_state->tag.value()};
}

void World::setEmitter(EmitterId id, const EmitterDef& def) {
    m_state->changing("World::setEmitter");
    const uint32_t i = checkedId(id, m_state->emitters.size(), "World::setEmitter", "emitter",
                                 m_state->tag.value());
    validateEmitter(def, "World::setEmitter");
    detail::EmitterState& e = m_state->emitters[i];
    if (def.seed != e.def.seed) {
        e.random = def.seed; // a new seed restarts the generator
    }
    e.def = def;
}

const EmitterDef& World::emitter(EmitterId id) const {
    return m_state
        ->emitters[checkedId(id, m_state->emitters.size(), "World::emitter", "emitter",
                             m_state->tag.value())]
        .def;
}

uint32_t World::emittedCount(EmitterId id) const {
    return m_state
        ->emitters[checkedId(id, m_state->emitters.size(), "World::emittedCount", "emitter",
                             m_state->tag.value())]
        .emitted;
}

uint32_t World::emitterCount() const {
    return static_cast<uint32_t>(m_state->emitters.size());
}

DrainId World::addDrain(const DrainDef& def) {
    m_state->changing("World::addDrain");
    validate(def.shape, "World::addDrain");
    if (def.onlyMaterial) {
        (void)material(def.material);
    }
    m_state->drains.push_back(def);
    return DrainId{static_cast<uint32_t>(m_state->drains.size() - 1), m_state->tag.value()};
}

const DrainDef& World::drain(DrainId id) const {
    return m_state->drains[checkedId(id, m_state->drains.size(), "World::drain", "drain",
                                     m_state->tag.value())];
}

uint32_t World::drainCount() const {
    return static_cast<uint32_t>(m_state->drains.size());
}

SensorId World::addSensor(const SensorDef& def) {
    m_state->changing("World::addSensor");
    validate(def.shape, "World::addSensor");
    m_state->sensors.push_back(def);
    // The new sensor's entries are zeros until the next step measures; the others keep theirs.
    // Only the new entries are written, so adding n sensors costs O(n) (the table is
    // sensor-major, one entry per material).
    try {
        m_state->sensorReadings.resize(m_state->sensors.size() * m_state->materials.size());
    } catch (...) {
        m_state->sensors.pop_back();
        throw;
    }
    return SensorId{static_cast<uint32_t>(m_state->sensors.size() - 1), m_state->tag.value()};
}

const SensorDef& World::sensor(SensorId id) const {
    return m_state->sensors[checkedId(id, m_state->sensors.size(), "World::sensor", "sensor",
                                      m_state->tag.value())];
}

uint32_t World::sensorCount() const {
    return static_cast<uint32_t>(m_state->sensors.size());
}

std::span<const SensorReading> World::sensorReading(SensorId id) const {
    const uint32_t i = checkedId(id, m_state->sensors.size(), "World::sensorReading", "sensor",
                                 m_state->tag.value());
    const size_t m = m_state->materials.size();
    return std::span<const SensorReading>(m_state->sensorReadings).subspan(i * m, m);
}

std::span<const RemovedEvent> World::removedEvents() const {
    return m_state->removed;
}

PositionBasedDef positionBasedPreset(Quality quality) {
    PositionBasedDef pb; // the game preset, the default
    if (quality == Quality::Precise) {
        pb.substeps = 4;
        pb.iterations = 8;
        pb.viscosityInterval = 1;
        pb.coarseCorrection = 0.0f;
    }
    return pb;
}

namespace {

// The frame the settings are tuned for (s): a longer frame takes proportionally more
// sub-steps (frameSubsteps). Frames up to kLongFrameSlack longer keep the setting's count, so
// a frame pacer's 1/59.94 s does not add a sub-step.
constexpr double kTunedFrame = 1.0 / 60.0;
constexpr double kLongFrameSlack = 0.1;

} // namespace

// The setting's count, or for a frame longer than the tuned one as many as keep each sub-step
// within the setting's at 60 Hz (a 1 s frame at 4 sub-steps takes 240).
uint32_t frameSubsteps(uint32_t perFrame, float frameDt) {
    checkFrameDt("fluid::frameSubsteps", frameDt);
    checkRange<uint32_t>("perFrame", perFrame, 1, 64, "count", "fluid::frameSubsteps: ");
    const double needed = double(frameDt) / kTunedFrame * double(perFrame);
    const double more = std::ceil(needed - kLongFrameSlack * double(perFrame));
    return more > double(perFrame) ? uint32_t(more) : perFrame; // frameDt <= 1 s: <= 66 x
}

uint32_t World::substepsFor(float frameDt) const {
    checkFrameDt("World::substepsFor", frameDt);
    const detail::WorldState& s = *m_state;
    if (s.def.solver != Solver::PositionBased) {
        return frameSubsteps(s.def.positionBased.substeps, frameDt);
    }
    return detail::dueSubsteps(s.carry + double(frameDt),
                               detail::substepLength(s.def.positionBased.substeps));
}

double World::substepLength() const {
    return detail::substepLength(m_state->def.positionBased.substeps);
}

double World::carriedTime() const {
    return m_state->carry;
}

namespace detail {

double substepLength(uint32_t perFrame) {
    // From the float 1/60 a game passes, so that its 60 Hz frames are whole sub-steps exactly
    // (at 4 per frame to the bit) and carry nothing.
    return double(1.0f / 60.0f) / double(perFrame);
}

uint32_t dueSubsteps(double due, double h) {
    // Rounded to the nearest: a frame a little short of a sub-step (a float's rounding of
    // 1/240, a frame timer's jitter) takes it and carries the shortfall as a negative time that
    // the next frames pay back, instead of waiting and then stepping twice. Frames of 1/240 s
    // with a jitter of +-1e-7 s step once each; a sub-step is skipped or doubled only when the
    // frames' sum has drifted half a sub-step from the sub-steps' (docs/position_based.md,
    // "Frame length"). A due under h / 2 gives 0, a negative one too (a carry from a longer
    // sub-step, before setPositionBased shortened it).
    const double nearest = std::floor(due / h + 0.5);
    return nearest > 0.0 ? uint32_t(nearest) : 0u;
}

} // namespace detail

void World::setPositionBased(const PositionBasedDef& settings) {
    m_state->changing("World::setPositionBased");
    validatePositionBased(settings, "World::setPositionBased: ");
    m_state->def.positionBased = settings;
}

uint32_t World::particleCount() const {
    return m_state->particles.size();
}
std::span<const float> World::positionX() const {
    return m_state->particles.px;
}
std::span<const float> World::positionY() const {
    return m_state->particles.py;
}
std::span<const float> World::velocityX() const {
    return m_state->particles.vx;
}
std::span<const float> World::velocityY() const {
    return m_state->particles.vy;
}
std::span<const float> World::density() const {
    return m_state->particles.density;
}
std::span<const float> World::stressXX() const {
    return m_state->particles.sxx;
}
std::span<const float> World::stressXY() const {
    return m_state->particles.sxy;
}
std::span<const float> World::pressure() const {
    return m_state->particles.pressure;
}
std::span<const uint16_t> World::materialIndex() const {
    return m_state->particles.material;
}
float Profile::stage(std::string_view name) const {
    for (const StageTime& t : stageTimes()) {
        if (name == t.name) {
            return t.ms;
        }
    }
    return 0.0f;
}

const Profile& World::profile() const {
    return m_state->profile;
}
uint32_t World::lastSubsteps() const {
    return m_state->profile.substeps;
}
double World::time() const {
    return m_state->time;
}
const WorldDef& World::def() const {
    return m_state->def;
}
float World::spacing(MaterialId id) const {
    return particleSpacing(material(id), m_state->def.depth);
}
float World::positionLimit() const {
    return m_state->positionLimit();
}

} // namespace fluid
