// fluid — the World API: materials, particles, handles, blobs, plugins.
#include "world_state.h"

#include <fluid/error.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fluid {

namespace {

std::string describe(ParticleHandle h) {
    std::ostringstream s;
    s << "{slot " << h.slot << ", generation " << h.generation << "}";
    return s.str();
}

bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

void checkVec(const char* function, const char* what, glm::vec2 v) {
    if (!finite(v)) {
        std::ostringstream s;
        s << function << ": " << what << " = (" << v.x << ", " << v.y << ") is not finite";
        throw Error(s.str());
    }
}

template <class T>
void checkRange(const char* field, T value, T lo, T hi, const char* unit, const char* prefix = "WorldDef: ") {
    if (!(value >= lo && value <= hi)) { // NaN fails too
        std::ostringstream s;
        s << prefix << field << " = " << value << " is out of range [" << lo << ", " << hi
          << "] (unit: " << unit << ")";
        throw Error(s.str());
    }
}

void validatePositionBased(const PositionBasedDef& pb, const char* prefix) {
    const std::string field = prefix;
    checkRange<uint32_t>((field + "substeps").c_str(), pb.substeps, 1, 64, "count", "");
    checkRange<uint32_t>((field + "iterations").c_str(), pb.iterations, 1, 100, "count", "");
    checkRange((field + "vorticity").c_str(), pb.vorticity, 0.0f, 10.0f, "1", "");
}

void validate(const WorldDef& def) {
    if (!(def.soundSpeed == 0.0f || (def.soundSpeed >= 0.1f && def.soundSpeed <= 1e4f))) {
        std::ostringstream s;
        s << "WorldDef: soundSpeed = " << def.soundSpeed
          << " is out of range: 0 (derive from the scene) or [0.1, 10000] (unit: m/s)";
        throw Error(s.str());
    }
    checkRange("depth", def.depth, 1e-4f, 1e3f, "m");
    checkRange("courant", def.courant, 0.01f, 1.0f, "1");
    checkRange<uint32_t>("maxSubsteps", def.maxSubsteps, 1, 10000, "count");
    checkRange<uint32_t>("maxParticles", def.maxParticles, 1, 1u << 26, "count");
    validatePositionBased(def.positionBased, "WorldDef: positionBased.");
    if (def.tasks.enqueue == nullptr) {
        checkRange<uint32_t>("workerCount", def.workerCount, 1, 256, "count");
    } else {
        if (def.tasks.finish == nullptr) {
            throw Error("WorldDef: tasks.enqueue is set but tasks.finish is null");
        }
        checkRange<uint32_t>("tasks.workerCount", def.tasks.workerCount, 1, 256, "count");
    }
}

// Even-odd rule; points exactly on an edge count as whichever side the rule puts them.
bool insidePolygon(const std::vector<glm::vec2>& poly, glm::vec2 p) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const glm::vec2 a = poly[i];
        const glm::vec2 b = poly[j];
        if ((a.y > p.y) != (b.y > p.y)) {
            const float x = (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x;
            if (p.x < x) {
                inside = !inside;
            }
        }
    }
    return inside;
}

float cross(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

bool segmentsCross(glm::vec2 a, glm::vec2 b, glm::vec2 c, glm::vec2 d) {
    const float d1 = cross(b - a, c - a);
    const float d2 = cross(b - a, d - a);
    const float d3 = cross(d - c, a - c);
    const float d4 = cross(d - c, b - c);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

void validatePolygon(const std::vector<glm::vec2>& v) {
    if (v.size() < 3) {
        throw Error("spawnBlob: polygon has " + std::to_string(v.size()) +
                    " vertices; expected 3 or more");
    }
    float area2 = 0.0f;
    for (size_t i = 0; i < v.size(); ++i) {
        checkVec("spawnBlob", ("polygon vertex " + std::to_string(i)).c_str(), v[i]);
        area2 += cross(v[i], v[(i + 1) % v.size()]);
    }
    if (!(std::fabs(area2) > 0.0f)) {
        throw Error("spawnBlob: polygon has zero area");
    }
    const size_t n = v.size();
    for (size_t i = 0; i < n; ++i) {
        for (size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) {
                continue; // adjacent through the closing edge
            }
            if (segmentsCross(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
                throw Error("spawnBlob: polygon edges " + std::to_string(i) + " and " +
                            std::to_string(j) + " cross; expected a simple polygon");
            }
        }
    }
}

} // namespace

namespace detail {

std::optional<uint32_t> WorldState::findIndex(ParticleHandle handle) const {
    if (handle.isNull() || handle.slot >= slotGeneration.size() ||
        slotGeneration[handle.slot] != handle.generation || slotIndex[handle.slot] == UINT32_MAX) {
        return std::nullopt;
    }
    return slotIndex[handle.slot];
}

uint32_t WorldState::checkedIndex(ParticleHandle handle, const char* function) const {
    if (handle.isNull()) {
        throw Error(std::string(function) + ": null particle handle");
    }
    const std::optional<uint32_t> index = findIndex(handle);
    if (!index) {
        throw Error(std::string(function) + ": stale particle handle " + describe(handle) +
                    ": that particle was removed");
    }
    return *index;
}

void WorldState::removeAt(uint32_t index) {
    Particles& p = particles;
    const uint32_t last = p.size() - 1;
    const uint32_t slot = p.slot[index];
    slotIndex[slot] = UINT32_MAX;
    // Generation 0 is the null handle's: skip it when a slot's counter wraps.
    slotGeneration[slot] = slotGeneration[slot] + 1 == 0 ? 1 : slotGeneration[slot] + 1;
    freeSlots.push_back(slot);
    if (index != last) {
        p.px[index] = p.px[last];
        p.py[index] = p.py[last];
        p.vx[index] = p.vx[last];
        p.vy[index] = p.vy[last];
        p.material[index] = p.material[last];
        p.slot[index] = p.slot[last];
        p.density[index] = p.density[last];
        p.pressure[index] = p.pressure[last];
        slotIndex[p.slot[index]] = index;
    }
    for (auto* channel : {&p.px, &p.py, &p.vx, &p.vy, &p.density, &p.pressure}) {
        channel->pop_back();
    }
    p.material.pop_back();
    p.slot.pop_back();
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

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

MaterialId World::addMaterial(const Material& material) {
    validate(material);
    if (m_state->materials.size() >= 65535) {
        throw Error("World::addMaterial: the world already has 65535 materials");
    }
    m_state->materials.push_back(material);
    return MaterialId{static_cast<uint16_t>(m_state->materials.size() - 1)};
}

void World::setMaterial(MaterialId id, const Material& material) {
    (void)this->material(id);
    validate(material);
    m_state->materials[id.index] = material;
}

const Material& World::material(MaterialId id) const {
    if (id.index >= m_state->materials.size()) {
        throw Error("unknown material id " + std::to_string(id.index) + "; the world has " +
                    std::to_string(m_state->materials.size()) + " materials");
    }
    return m_state->materials[id.index];
}

uint32_t World::materialCount() const { return static_cast<uint32_t>(m_state->materials.size()); }

ParticleHandle World::addParticle(glm::vec2 position, glm::vec2 velocity, MaterialId materialId) {
    checkVec("World::addParticle", "position", position);
    checkVec("World::addParticle", "velocity", velocity);
    (void)material(materialId);
    detail::WorldState& s = *m_state;
    if (s.particles.size() >= s.def.maxParticles) {
        throw Error("World::addParticle: particle cap exceeded: the world holds maxParticles = " +
                    std::to_string(s.def.maxParticles) + " particles");
    }
    uint32_t slot = 0;
    if (!s.freeSlots.empty()) {
        slot = s.freeSlots.back();
        s.freeSlots.pop_back();
    } else {
        slot = static_cast<uint32_t>(s.slotIndex.size());
        s.slotIndex.push_back(UINT32_MAX);
        s.slotGeneration.push_back(1);
    }
    detail::Particles& p = s.particles;
    s.slotIndex[slot] = p.size();
    p.px.push_back(position.x);
    p.py.push_back(position.y);
    p.vx.push_back(velocity.x);
    p.vy.push_back(velocity.y);
    p.material.push_back(materialId.index);
    p.slot.push_back(slot);
    p.density.push_back(0.0f);
    p.pressure.push_back(0.0f);
    return ParticleHandle{slot, s.slotGeneration[slot]};
}

uint32_t World::spawnBlob(const BlobDef& blob) {
    const Material& mat = material(blob.material);
    checkVec("spawnBlob", "velocity", blob.velocity);
    glm::vec2 lo{}, hi{};
    switch (blob.shape) {
    case BlobShape::Rectangle:
        checkVec("spawnBlob", "center", blob.center);
        if (!(blob.halfExtents.x > 0.0f && blob.halfExtents.y > 0.0f) || !finite(blob.halfExtents)) {
            std::ostringstream s;
            s << "spawnBlob: halfExtents = (" << blob.halfExtents.x << ", " << blob.halfExtents.y
              << ") must be finite and > 0 (unit: m)";
            throw Error(s.str());
        }
        lo = blob.center - blob.halfExtents;
        hi = blob.center + blob.halfExtents;
        break;
    case BlobShape::Circle:
        checkVec("spawnBlob", "center", blob.center);
        if (!(blob.radius > 0.0f) || !std::isfinite(blob.radius)) {
            std::ostringstream s;
            s << "spawnBlob: radius = " << blob.radius << " must be finite and > 0 (unit: m)";
            throw Error(s.str());
        }
        lo = blob.center - glm::vec2(blob.radius);
        hi = blob.center + glm::vec2(blob.radius);
        break;
    case BlobShape::Polygon:
        validatePolygon(blob.vertices);
        lo = hi = blob.vertices[0];
        for (glm::vec2 v : blob.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        break;
    }
    const float spacing = particleSpacing(mat, m_state->def.depth);
    const double cols = std::floor(double(hi.x - lo.x) / spacing);
    const double rows = std::floor(double(hi.y - lo.y) / spacing);
    if (cols * rows > double(m_state->def.maxParticles)) {
        throw Error("spawnBlob: particle cap exceeded: the blob needs about " +
                    std::to_string(uint64_t(cols * rows)) + " particles; maxParticles = " +
                    std::to_string(m_state->def.maxParticles));
    }
    // Lattice points at cell centres, spacing apart, centred in the shape's bounding box.
    const auto nx = static_cast<uint32_t>(cols);
    const auto ny = static_cast<uint32_t>(rows);
    const glm::vec2 origin =
        0.5f * (lo + hi) - 0.5f * spacing * glm::vec2(float(nx) - 1.0f, float(ny) - 1.0f);
    std::vector<glm::vec2> points;
    for (uint32_t j = 0; j < ny; ++j) {
        for (uint32_t i = 0; i < nx; ++i) {
            const glm::vec2 p = origin + spacing * glm::vec2(float(i), float(j));
            bool inside = true;
            if (blob.shape == BlobShape::Circle) {
                const glm::vec2 d = p - blob.center;
                inside = d.x * d.x + d.y * d.y <= blob.radius * blob.radius;
            } else if (blob.shape == BlobShape::Polygon) {
                inside = insidePolygon(blob.vertices, p);
            }
            if (inside) {
                points.push_back(p);
            }
        }
    }
    if (m_state->particles.size() + points.size() > m_state->def.maxParticles) {
        throw Error("spawnBlob: particle cap exceeded: " + std::to_string(points.size()) +
                    " more particles would pass maxParticles = " +
                    std::to_string(m_state->def.maxParticles));
    }
    for (glm::vec2 p : points) {
        addParticle(p, blob.velocity, blob.material);
    }
    return static_cast<uint32_t>(points.size());
}

void World::removeParticle(ParticleHandle handle) {
    m_state->removeAt(m_state->checkedIndex(handle, "World::removeParticle"));
}

bool World::isValid(ParticleHandle handle) const { return indexOf(handle).has_value(); }

std::optional<uint32_t> World::indexOf(ParticleHandle handle) const {
    return m_state->findIndex(handle);
}

ParticleHandle World::handleAt(uint32_t index) const {
    if (index >= particleCount()) {
        throw Error("World::handleAt: index " + std::to_string(index) + " is out of range; the world has " +
                    std::to_string(particleCount()) + " particles");
    }
    const uint32_t slot = m_state->particles.slot[index];
    return ParticleHandle{slot, m_state->slotGeneration[slot]};
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
    const uint32_t i = m_state->checkedIndex(handle, "World::setVelocity");
    checkVec("World::setVelocity", "velocity", velocity);
    m_state->particles.vx[i] = velocity.x;
    m_state->particles.vy[i] = velocity.y;
}

ForcePlugin& World::addForce(std::unique_ptr<ForcePlugin> plugin) {
    if (!plugin) {
        throw Error("World::addForce: null plugin");
    }
    m_state->forces.push_back(std::move(plugin));
    return *m_state->forces.back();
}

BoundaryPlugin& World::addBoundary(std::unique_ptr<BoundaryPlugin> plugin) {
    if (!plugin) {
        throw Error("World::addBoundary: null plugin");
    }
    m_state->boundaries.push_back(std::move(plugin));
    return *m_state->boundaries.back();
}

std::span<const std::unique_ptr<ForcePlugin>> World::forces() const { return m_state->forces; }
std::span<const std::unique_ptr<BoundaryPlugin>> World::boundaries() const {
    return m_state->boundaries;
}

void World::step(float frameDt) {
    if (!std::isfinite(frameDt) || !(frameDt > 0.0f) || frameDt > 1.0f) {
        std::ostringstream s;
        s << "World::step: frameDt = " << frameDt
          << " s is out of range; expected a finite value in (0, 1] (typically 1/60)";
        throw Error(s.str());
    }
    if (m_state->materials.empty()) {
        throw Error("World::step: the world has no material; call addMaterial first");
    }
    switch (m_state->def.solver) {
    case Solver::PositionBased:
        detail::stepPositionBased(*m_state, frameDt);
        break;
    case Solver::Explicit:
        detail::stepExplicit(*m_state, frameDt);
        break;
    }
}

void World::setPositionBased(const PositionBasedDef& settings) {
    validatePositionBased(settings, "World::setPositionBased: ");
    m_state->def.positionBased = settings;
}

uint32_t World::particleCount() const { return m_state->particles.size(); }
std::span<const float> World::positionX() const { return m_state->particles.px; }
std::span<const float> World::positionY() const { return m_state->particles.py; }
std::span<const float> World::velocityX() const { return m_state->particles.vx; }
std::span<const float> World::velocityY() const { return m_state->particles.vy; }
std::span<const float> World::density() const { return m_state->particles.density; }
std::span<const float> World::pressure() const { return m_state->particles.pressure; }
std::span<const uint16_t> World::materialIndex() const { return m_state->particles.material; }
const Profile& World::profile() const { return m_state->profile; }
uint32_t World::lastSubsteps() const { return m_state->profile.substeps; }
double World::time() const { return m_state->time; }
const WorldDef& World::def() const { return m_state->def; }
float World::spacing(MaterialId id) const { return particleSpacing(material(id), m_state->def.depth); }

} // namespace fluid
