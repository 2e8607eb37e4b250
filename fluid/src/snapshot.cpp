// fluid — snapshots: the whole world in a binary file, restored bit-identically.
//
// Layout (little-endian, as the machine stores it; a snapshot is read back by the same build
// family, not exchanged across architectures):
//   "FLUIDSNP"            8 bytes magic
//   u32 version           kVersion
//   u64 payload size      bytes that follow, before the checksum
//   payload               sections in the order of `writeWorld`
//   u64 checksum          FNV-1a 64 of the payload
// A truncated file fails the size check, a flipped byte the checksum; both before anything is
// built from the payload.
#include "world_state.h"

#include <fluid/error.h>
#include <fluid/groups.h>
#include <fluid/internal/binary.h>
#include <fluid/registry.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <istream>
#include <optional>
#include <ostream>
#include <sstream>
#include <tuple>

namespace fluid {

namespace {

constexpr char kMagic[8] = {'F', 'L', 'U', 'I', 'D', 'S', 'N', 'P'};
constexpr uint32_t kVersion = 7; // 4: Herschel-Bulkley fields, stress and pending kicks; 5: the
                                 // position-based solver's carried frame time; 6: the yielding
                                 // particles' structure (Particles::structure); 7: groups, user
                                 // data, colours and interpolation (groups.h), a last section
// The oldest version this build reads: a version 6 snapshot loads without that last section
// (no groups but the emitters' own, no user data or colours, interpolation off).
constexpr uint32_t kOldestVersion = 6;

// The last step's profile as a snapshot holds it: its counts and figures, in the order of the
// format since version 2. The eight floats where the stage times once stood are written as 0
// and skipped on reading: stage times are wall-clock readings, not state, so two saves of the
// same state give the same bytes and a loaded world reads no stages.
struct ProfileRecord {
    float times[8] = {};
    uint32_t substeps = 0, iterations = 0;
    float cflDt = 0, soundSpeed = 0, densityErrorMax = 0, densityErrorAvg = 0;
    uint32_t speedClamped = 0, nonFiniteRepaired = 0, forceDropped = 0;
    int32_t forceDroppedPlugin = -1;
    uint32_t separated = 0, particles = 0, emitted = 0, emitBlocked = 0, emitSkipped = 0,
             removed = 0;

    static ProfileRecord of(const Profile& p) {
        return {{},
                p.substeps,
                p.iterations,
                p.cflDt,
                p.soundSpeed,
                p.densityErrorMax,
                p.densityErrorAvg,
                p.speedClamped,
                p.nonFiniteRepaired,
                p.forceDropped,
                p.forceDroppedPlugin,
                p.separated,
                p.particles,
                p.emitted,
                p.emitBlocked,
                p.emitSkipped,
                p.removed};
    }
    Profile profile() const {
        Profile p;
        p.substeps = substeps;
        p.iterations = iterations;
        p.cflDt = cflDt;
        p.soundSpeed = soundSpeed;
        p.densityErrorMax = densityErrorMax;
        p.densityErrorAvg = densityErrorAvg;
        p.speedClamped = speedClamped;
        p.nonFiniteRepaired = nonFiniteRepaired;
        p.forceDropped = forceDropped;
        p.forceDroppedPlugin = forceDroppedPlugin;
        p.separated = separated;
        p.particles = particles;
        p.emitted = emitted;
        p.emitBlocked = emitBlocked;
        p.emitSkipped = emitSkipped;
        p.removed = removed;
        return p;
    }
};
static_assert(sizeof(ProfileRecord) == 24 * 4, "the snapshot's profile record has no padding");

using In = internal::ByteReader;
using Out = internal::ByteWriter;

// The numbers of a definition struct, each as its member's type, in the table's order.
template <class Def> void putFields(Out& o, std::span<const Field<Def>> fields, const Def& def) {
    for (const Field<Def>& f : fields) {
        if (f.whole != nullptr) {
            o.put(def.*f.whole);
        } else {
            o.put(def.*f.real);
        }
    }
}

// Reads what `putFields` wrote.
template <class Def> void getFields(In& in, std::span<const Field<Def>> fields, Def& def) {
    for (const Field<Def>& f : fields) {
        if (f.whole != nullptr) {
            def.*f.whole = in.get<uint32_t>(f.name.data());
        } else {
            def.*f.real = in.get<float>(f.name.data());
        }
    }
}

// Throws "snapshot: corrupt: <message>", as the reader does.
[[noreturn]] void corrupt(const std::string& message) {
    throw Error("snapshot: corrupt: " + message, ErrorCode::BadFile);
}

void putShape(Out& o, const Shape& s) {
    o.put(uint8_t(s.type));
    o.put(s.center);
    o.put(s.halfExtents);
    o.put(s.radius);
    o.array(s.vertices);
}

Shape getShape(In& in) {
    Shape s;
    s.type = in.small(ShapeType::Polygon, "a shape type");
    s.center = in.get<glm::vec2>();
    s.halfExtents = in.get<glm::vec2>();
    s.radius = in.get<float>();
    in.array(s.vertices, "a shape's vertex list");
    validate(s, "snapshot: corrupt shape");
    return s;
}

void putPlugin(Out& o, const Plugin& plugin) {
    o.string(std::string(plugin.type()));
    const std::span<const ParamDecl> decls = plugin.params();
    o.put<uint64_t>(decls.size());
    for (const ParamDecl& decl : decls) {
        o.string(std::string(decl.name));
        if (decl.type == ParamType::Number) {
            o.put(plugin.param(decl.name));
        } else {
            const std::span<const glm::vec2> pts = plugin.points(decl.name);
            o.array(std::vector<glm::vec2>(pts.begin(), pts.end()));
        }
    }
    StateWriter state;
    plugin.saveState(state);
    o.array(state.bytes());
}

// A plugin as the snapshot holds it: its parameters go through the plugin's own checks, each
// value (`setParam`, `setPoints`) and then all together (`checkParams`, as `Registry::create`
// and the level loader do), so a snapshot cannot hold a plugin the API would have refused (an
// empty box that loads and then fails every step). `index` is its place among the world's
// forces or boundaries, which the error names.
std::unique_ptr<Plugin> getPlugin(In& in, const Registry& registry, PluginKind kind,
                                  uint64_t index) {
    const std::string type = in.string("a plugin type");
    if (registry.find(type) == nullptr) {
        throw Error("snapshot: plugin type '" + type +
                        "' is not in the registry; register it (or load its plugin library) "
                        "before loading the snapshot",
                    ErrorCode::UnknownName);
    }
    std::unique_ptr<Plugin> plugin = registry.create(type);
    if (plugin->kind() != kind) {
        corrupt("plugin '" + type + "' is stored as the wrong kind");
    }
    const auto count = in.get<uint64_t>();
    if (count != plugin->params().size()) {
        throw Error("snapshot: plugin '" + type + "' was saved with " + std::to_string(count) +
                        " parameters; this build declares " +
                        std::to_string(plugin->params().size()),
                    ErrorCode::BadFile);
    }
    const std::string where = std::string("snapshot: ") +
                              (kind == PluginKind::Force ? "force" : "boundary") + " plugin " +
                              std::to_string(index) + ": ";
    const auto checked = [&](const auto& set) {
        try {
            set();
        } catch (const Error& e) {
            throw Error(where + e.what(), ErrorCode::BadFile);
        }
    };
    for (const ParamDecl& decl : plugin->params()) {
        const std::string name = in.string("a parameter name");
        if (name != decl.name) {
            throw Error("snapshot: plugin '" + type + "' parameter '" + name +
                            "' does not match this build's '" + std::string(decl.name) + "'",
                        ErrorCode::BadFile);
        }
        if (decl.type == ParamType::Number) {
            const double value = in.get<double>();
            checked([&] { plugin->setParam(name, value); });
        } else {
            std::vector<glm::vec2> pts;
            in.array(pts, "a point list");
            checked([&] { plugin->setPoints(name, pts); });
        }
    }
    checked([&] { plugin->checkParams(); });
    std::vector<std::byte> state;
    in.array(state, "a plugin state");
    StateReader reader(state);
    plugin->restoreState(reader);
    if (reader.remaining() != 0) {
        corrupt("plugin '" + type + "' left " + std::to_string(reader.remaining()) +
                " bytes of its state unread");
    }
    return plugin;
}

// Everything the step and the handle API rely on: equal channel lengths, finite positions and
// velocities, known materials, and a handle table in which every slot is either free (listed
// once in freeSlots) or names the particle that names it back.
void checkParticles(const detail::WorldState& s) {
    const detail::Particles& p = s.particles;
    const size_t n = p.px.size();
    for (const std::vector<float>* channel : p.keptFloats()) {
        if (channel->size() != n) {
            corrupt("particle channels of different lengths");
        }
    }
    if (p.material.size() != n || p.slot.size() != n || p.expiry.size() != n ||
        s.slotGeneration.size() != s.slotIndex.size() || n > s.def.maxParticles) {
        corrupt("particle channels or handle table of inconsistent sizes");
    }
    const std::pair<const char*, const std::vector<float>*> state[] = {
        {"x", &p.px}, {"y", &p.py},     {"vx", &p.vx}, {"vy", &p.vy},
        {"sxx", &p.sxx}, {"sxy", &p.sxy}, {"structure", &p.structure}, {"kx", &p.kx},
        {"ky", &p.ky}};
    const float limit = s.positionLimit();
    for (size_t i = 0; i < n; ++i) {
        for (const auto& [name, channel] : state) {
            if (!std::isfinite((*channel)[i])) {
                std::ostringstream text;
                text << "particle " << i << " " << name << " = " << (*channel)[i]
                     << " is not finite";
                corrupt(text.str());
            }
        }
        if (!(std::fabs(p.px[i]) <= limit && std::fabs(p.py[i]) <= limit)) {
            std::ostringstream text;
            text << "particle " << i << " at (" << p.px[i] << ", " << p.py[i]
                 << ") is outside the position range [" << -limit << ", " << limit << "] m";
            corrupt(text.str());
        }
        if (std::isnan(p.expiry[i]) || p.material[i] >= s.materials.size() ||
            p.slot[i] >= s.slotIndex.size() || s.slotIndex[p.slot[i]] != i) {
            corrupt("particle " + std::to_string(i) +
                    " has a non-finite state, a bad material or a bad handle");
        }
        if ((p.sxx[i] != 0.0f || p.sxy[i] != 0.0f || p.structure[i] != 0.0f) &&
            !hasYield(s.materials[p.material[i]])) {
            corrupt("particle " + std::to_string(i) +
                    " holds a stress, but its material has no yield stress or consistency");
        }
        if (!(p.structure[i] >= 0.0f && p.structure[i] <= 1.0f)) {
            corrupt("particle " + std::to_string(i) + " structure = " +
                    std::to_string(p.structure[i]) + " is outside [0, 1]");
        }
    }
    std::vector<uint8_t> free(s.slotIndex.size(), 0);
    for (uint32_t slot : s.freeSlots) {
        if (slot >= s.slotIndex.size() || s.slotIndex[slot] != UINT32_MAX || free[slot] != 0) {
            corrupt("a free slot is in use or listed twice");
        }
        free[slot] = 1;
    }
    for (size_t slot = 0; slot < s.slotIndex.size(); ++slot) {
        const uint32_t index = s.slotIndex[slot];
        const bool used = index != UINT32_MAX && index < n && p.slot[index] == slot;
        if (!(used || (index == UINT32_MAX && free[slot] != 0)) || s.slotGeneration[slot] == 0) {
            corrupt("handle slot " + std::to_string(slot) + " is neither used nor free");
        }
    }
}

// The solver state carried between steps: finite, the sound speed and acceleration not
// negative.
void checkSolverState(const detail::WorldState& s) {
    const std::tuple<const char*, double, double> solver[] = {
        {"time", s.time, -DBL_MAX},
        {"carried time", s.carry, -DBL_MAX}, // its range: World::load
        {"sound speed", s.soundSpeed, 0.0},
        {"field gh", s.fieldGH, -DBL_MAX},
        {"last max acceleration", s.lastMaxAccel, 0.0}};
    for (const auto& [name, value, lowest] : solver) {
        if (!std::isfinite(value) || value < lowest) {
            std::ostringstream text;
            text << "the solver state is not finite: " << name << " = " << value;
            corrupt(text.str());
        }
    }
}

// Version 7's last section (groups.h): interpolation on, the colour mixing rate, the group
// table, membership, user data and colour fractions per handle slot (as long as the handle
// table, or empty when unused), each emitter's group, and the colour channel (empty when unused). The previous
// positions are not saved: a loaded world's are its current ones.
void putGroups(Out& o, const detail::WorldState& s) {
    o.put(uint8_t(s.interpolate ? (s.interpolateSteps ? 2 : 1) : 0)); // Interpolation
    o.put(s.colourMixing);
    o.put<uint64_t>(s.groups.size());
    for (const detail::WorldState::Group& g : s.groups) {
        o.put(g.generation);
        o.put(g.count);
        o.put(uint8_t(g.live));
        o.put(g.userData);
        o.put(g.colour);
    }
    o.array(s.freeGroups);
    const auto padded = [&](const std::vector<uint32_t>& perSlot, uint32_t none) {
        std::vector<uint32_t> out;
        if (!perSlot.empty()) {
            out.assign(s.slotIndex.size(), none);
            std::copy_n(perSlot.begin(), std::min(perSlot.size(), out.size()), out.begin());
        }
        return out;
    };
    o.array(padded(s.slotGroup, detail::WorldState::kNoGroup));
    o.array(padded(s.slotUserData, 0u));
    o.array(padded(s.slotColourFraction, 0u));
    o.array(s.emitterGroup);
    o.array(s.particles.colour);
}

// Reads what `putGroups` wrote and checks it against the particles and emitters read before.
void getGroups(In& in, detail::WorldState& s) {
    using detail::WorldState;
    const Interpolation mode = in.small(Interpolation::Step, "the interpolation mode");
    s.interpolate = mode != Interpolation::Off;
    s.interpolateSteps = mode == Interpolation::Step;
    s.colourMixing = in.get<float>("the colour mixing rate");
    if (!(s.colourMixing >= 0.0f && s.colourMixing <= 1000.0f)) {
        std::ostringstream text;
        text << "the colour mixing rate " << s.colourMixing << " is outside [0, 1000] 1/s";
        corrupt(text.str());
    }
    const auto count = in.get<uint64_t>("the group count");
    if (count > uint64_t(s.slotIndex.size()) + s.emitters.size() + (uint64_t(1) << 24)) {
        corrupt("the group count " + std::to_string(count) + " is implausible");
    }
    s.groups.assign(size_t(count), {});
    for (WorldState::Group& g : s.groups) {
        g.generation = in.get<uint32_t>("a group's generation");
        g.count = in.get<uint32_t>("a group's count");
        g.live = in.small(true, "a group's live flag");
        g.userData = in.get<uint32_t>("a group's user data");
        g.colour = in.get<uint32_t>("a group's colour");
        if (g.generation == 0) {
            corrupt("a group has generation 0");
        }
    }
    in.array(s.freeGroups, "the free groups");
    in.array(s.slotGroup, "the particles' groups");
    in.array(s.slotUserData, "the particles' user data");
    in.array(s.slotColourFraction, "the colours' fractions");
    in.array(s.emitterGroup, "the emitters' groups");
    in.array(s.particles.colour, "the colour channel");
    std::vector<uint8_t> listed(s.groups.size(), 0);
    for (const uint32_t g : s.freeGroups) {
        if (g >= s.groups.size() || s.groups[g].live || listed[g] != 0) {
            corrupt("a free group is in use or listed twice");
        }
        listed[g] = 1;
    }
    for (size_t g = 0; g < s.groups.size(); ++g) {
        if (!s.groups[g].live && listed[g] == 0) {
            corrupt("group " + std::to_string(g) + " is neither live nor free");
        }
    }
    const size_t slots = s.slotIndex.size();
    if ((!s.slotGroup.empty() && s.slotGroup.size() != slots) ||
        (!s.slotUserData.empty() && s.slotUserData.size() != slots) ||
        (!s.slotColourFraction.empty() && s.slotColourFraction.size() != slots) ||
        s.emitterGroup.size() != s.emitters.size() ||
        (!s.particles.colour.empty() && s.particles.colour.size() != s.particles.size())) {
        corrupt("group, user data or colour channels of inconsistent sizes");
    }
    std::vector<uint32_t> counted(s.groups.size(), 0);
    for (size_t slot = 0; slot < s.slotGroup.size(); ++slot) {
        const uint32_t g = s.slotGroup[slot];
        if (g == WorldState::kNoGroup) {
            continue;
        }
        if (g >= s.groups.size() || !s.groups[g].live || s.slotIndex[slot] == UINT32_MAX) {
            corrupt("handle slot " + std::to_string(slot) +
                    " is in a group that is not live, or is free and in a group");
        }
        ++counted[g];
    }
    for (size_t g = 0; g < s.groups.size(); ++g) {
        if (s.groups[g].count != counted[g]) {
            corrupt("group " + std::to_string(g) + " counts " +
                    std::to_string(s.groups[g].count) + " particles but has " +
                    std::to_string(counted[g]));
        }
    }
    for (const uint32_t g : s.emitterGroup) {
        if (g != WorldState::kNoGroup && (g >= s.groups.size() || !s.groups[g].live)) {
            corrupt("an emitter feeds a group that is not live");
        }
    }
    if (s.interpolate) {
        detail::resetPrevious(s);
    }
}

} // namespace

void World::save(std::ostream& out) const {
    m_state->checkIdle("World::save");
    const detail::WorldState& s = *m_state;
    Out o;
    // Settings (the task hook is the host's, not the world's).
    const WorldDef& d = s.def;
    o.put(uint8_t(d.solver));
    putFields(o, positionBasedFields(), d.positionBased);
    o.put(uint8_t(d.equationOfState));
    o.put(d.soundSpeed);
    putFields(o, worldFields(), d);
    o.put(d.workerCount);
    // Materials.
    o.put<uint64_t>(s.materials.size());
    for (const Material& m : s.materials) {
        putFields(o, materialFields(), m);
        o.string(m.name);
    }
    // Particles in their current order, and the handle table.
    const detail::Particles& p = s.particles;
    for (const std::vector<float>* channel : p.keptFloats()) {
        o.array(*channel);
    }
    o.array(p.material);
    o.array(p.slot);
    o.array(p.expiry);
    o.array(s.slotIndex);
    o.array(s.slotGeneration);
    o.array(s.freeSlots);
    // Plugins.
    o.put<uint64_t>(s.forces.size());
    for (const auto& plugin : s.forces) {
        putPlugin(o, *plugin);
    }
    o.put<uint64_t>(s.boundaries.size());
    for (const auto& plugin : s.boundaries) {
        putPlugin(o, *plugin);
    }
    // Emitters, drains, sensors and the last step's readings.
    o.put<uint64_t>(s.emitters.size());
    for (const detail::EmitterState& e : s.emitters) {
        // Field by field, not from emitterFields(): the format puts the material between rate
        // and maxCount.
        const EmitterDef& ed = e.def;
        o.put(ed.position);
        o.put(ed.direction);
        o.put(ed.speed);
        o.put(ed.width);
        o.put(ed.rate);
        o.put(ed.material.index);
        o.put(ed.maxCount);
        o.put(ed.lifetime);
        o.put(ed.jitter);
        o.put(ed.seed);
        o.put(e.carry);
        o.put(e.emitted);
        o.put(e.random);
    }
    o.put<uint64_t>(s.drains.size());
    for (const DrainDef& dr : s.drains) {
        putShape(o, dr.shape);
        o.put(uint8_t(dr.onlyMaterial));
        o.put(dr.material.index);
    }
    o.put<uint64_t>(s.sensors.size());
    for (const SensorDef& se : s.sensors) {
        putShape(o, se.shape);
    }
    o.array(s.sensorReadings); // the last step's removal events are not kept: they describe it

    // Solver state carried from step to step, and the last profile's counts and figures
    // (ProfileRecord: no stage times).
    o.put(s.time);
    o.put(s.carry);
    o.put(s.soundSpeed);
    o.put(s.fieldGH);
    o.put(uint8_t(s.fieldMeasured));
    o.put(s.lastMaxAccel);
    o.put(ProfileRecord::of(s.profile));
    putGroups(o, s);

    out.write(kMagic, sizeof(kMagic));
    const uint32_t version = kVersion;
    const uint64_t size = o.bytes.size();
    const uint64_t sum = internal::fnv1a(o.bytes);
    out.write(reinterpret_cast<const char*>(&version), sizeof(version));
    out.write(reinterpret_cast<const char*>(&size), sizeof(size));
    out.write(reinterpret_cast<const char*>(o.bytes.data()), std::streamsize(o.bytes.size()));
    out.write(reinterpret_cast<const char*>(&sum), sizeof(sum));
    if (!out) {
        throw Error("World::save: writing the snapshot failed", ErrorCode::Io);
    }
}

void World::saveFile(const std::string& path) const {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    if (!file) {
        throw Error("World::saveFile: cannot open '" + path + "' for writing", ErrorCode::Io);
    }
    save(file);
    file.close();
    if (!file) {
        throw Error("World::saveFile: writing '" + path + "' failed", ErrorCode::Io);
    }
}

namespace {

// Bytes left in `in` after its position (unit: bytes), or nothing when the stream cannot tell
// (a pipe).
std::optional<uint64_t> remainingBytes(std::istream& in) {
    const std::istream::pos_type at = in.tellg();
    if (at == std::istream::pos_type(-1) || !in.seekg(0, std::ios::end)) {
        in.clear();
        return std::nullopt;
    }
    const std::istream::pos_type end = in.tellg();
    in.seekg(at);
    if (end == std::istream::pos_type(-1) || !in) {
        in.clear();
        return std::nullopt;
    }
    return end >= at ? uint64_t(end - at) : 0;
}

// Reads up to `n` bytes (fewer at the end of the stream), growing the buffer only as bytes
// arrive: a size a corrupt header promises is never allocated before it is there.
std::vector<char> readUpTo(std::istream& in, uint64_t n) {
    std::vector<char> out;
    constexpr uint64_t kChunk = uint64_t(1) << 20;
    while (out.size() < n) {
        const std::size_t want = std::size_t(std::min(kChunk, n - out.size()));
        const std::size_t had = out.size();
        out.resize(had + want);
        in.read(out.data() + had, std::streamsize(want));
        out.resize(had + std::size_t(in.gcount()));
        if (std::size_t(in.gcount()) < want) {
            break;
        }
    }
    return out;
}

// The payload and checksum of a snapshot: the header (magic, version, payload size) is read
// and checked first, and the size against the bytes the stream holds, before the body is read
// or anything is sized by it (a huge file of another version is refused after 20 bytes).
std::vector<char> readBody(std::istream& input, uint64_t& size, uint32_t& version) {
    char header[sizeof(kMagic) + sizeof(uint32_t) + sizeof(uint64_t)];
    input.read(header, sizeof(header));
    if (std::size_t(input.gcount()) < sizeof(header) ||
        std::memcmp(header, kMagic, sizeof(kMagic)) != 0) {
        throw Error("snapshot: not a fluid snapshot (no FLUIDSNP header)", ErrorCode::BadFile);
    }
    std::memcpy(&version, header + sizeof(kMagic), sizeof(version));
    std::memcpy(&size, header + sizeof(kMagic) + sizeof(version), sizeof(size));
    if (version < kOldestVersion || version > kVersion) {
        throw Error("snapshot: format version " + std::to_string(version) +
                        " is not supported; this fluid reads versions " +
                        std::to_string(kOldestVersion) + " to " + std::to_string(kVersion),
                    ErrorCode::BadFile);
    }
    const auto refuse = [&](uint64_t holds) {
        std::ostringstream s;
        s << "snapshot: truncated or padded: the header promises " << size
          << " bytes of data and a checksum, the file holds " << holds
          << " bytes after the header";
        throw Error(s.str(), ErrorCode::BadFile);
    };
    const std::optional<uint64_t> remaining = remainingBytes(input);
    const bool fits = size <= UINT64_MAX - sizeof(uint64_t);
    if (remaining && (!fits || *remaining != size + sizeof(uint64_t))) {
        refuse(*remaining);
    }
    std::vector<char> body = readUpTo(input, fits ? size + sizeof(uint64_t) : UINT64_MAX);
    if (!remaining && (!fits || body.size() != size + sizeof(uint64_t) ||
                       input.peek() != std::char_traits<char>::eof())) {
        uint64_t holds = body.size();
        char scratch[4096];
        while (input.read(scratch, sizeof(scratch)) || input.gcount() > 0) {
            holds += uint64_t(input.gcount());
        }
        refuse(holds);
    }
    return body;
}

// The world's settings as `World::save` wrote them (the task hook not included).
WorldDef getWorldDef(In& in) {
    WorldDef def;
    def.solver = in.small(Solver::Explicit, "the solver");
    getFields(in, positionBasedFields(), def.positionBased);
    def.equationOfState = in.small(EquationOfState::Tait, "the equation of state");
    def.soundSpeed = in.get<float>("the sound speed");
    getFields(in, worldFields(), def);
    def.workerCount = in.get<uint32_t>("the worker count");
    return def;
}

// One material (checked by World::addMaterial).
Material getMaterial(In& in) {
    Material m;
    getFields(in, materialFields(), m);
    m.name = in.string("a material name");
    return m;
}

// One emitter's settings (checked by World::addEmitter) ...
EmitterDef getEmitterDef(In& in) {
    EmitterDef ed;
    ed.position = in.get<glm::vec2>();
    ed.direction = in.get<glm::vec2>();
    ed.speed = in.get<float>();
    ed.width = in.get<float>();
    ed.rate = in.get<float>();
    ed.material = MaterialId{in.get<uint16_t>("an emitter's material")};
    ed.maxCount = in.get<uint32_t>();
    ed.lifetime = in.get<float>();
    ed.jitter = in.get<float>();
    ed.seed = in.get<uint64_t>();
    return ed;
}

// ... and its clock and random state.
void getEmitterClock(In& in, detail::EmitterState& e) {
    e.carry = in.get<double>();
    e.emitted = in.get<uint32_t>();
    e.random = in.get<uint64_t>();
    if (!(e.carry >= 0.0 && e.carry < 1.0)) {
        corrupt("an emitter's clock is outside [0, 1)");
    }
}

} // namespace

World World::load(std::istream& input, const Registry& registry, uint32_t workerCount,
                  const TaskHook& tasks) {
    // What the snapshot holds goes through the checks the API runs on the same values (World's
    // settings, addMaterial, addForce...): a value they refuse is the file's fault, so their
    // bad-argument, out-of-range and stale-id errors leave here as ErrorCode::BadFile, the
    // message as it was.
    const auto read = [&]() -> World {
        uint64_t size = 0;
        uint32_t version = 0;
        const std::vector<char> body = readBody(input, size, version);
        uint64_t sum = 0;
        std::memcpy(&sum, body.data() + size, sizeof(sum));
        if (internal::fnv1a(std::string_view(body.data(), size)) != sum) {
            corrupt("checksum mismatch");
        }
        In in(std::string_view(body.data(), size), "snapshot: corrupt");

        WorldDef def = getWorldDef(in);
        if (workerCount > 0) {
            def.workerCount = workerCount;
        }
        def.tasks = tasks;
        World world(def); // validates the settings
        detail::WorldState& s = *world.m_state;

        const auto materials = in.get<uint64_t>();
        for (uint64_t k = 0; k < materials; ++k) {
            world.addMaterial(getMaterial(in));
        }
        detail::Particles& p = s.particles;
        for (std::vector<float>* channel : p.keptFloats()) {
            in.array(*channel, "a particle channel");
        }
        in.array(p.material, "the material channel");
        in.array(p.slot, "the slot channel");
        in.array(p.expiry, "the expiry channel");
        in.array(s.slotIndex, "the handle table");
        in.array(s.slotGeneration, "the handle generations");
        in.array(s.freeSlots, "the free slots");
        checkParticles(s);
        s.kicksPending = std::any_of(p.kx.begin(), p.kx.end(), [](float k) { return k != 0.0f; }) ||
                         std::any_of(p.ky.begin(), p.ky.end(), [](float k) { return k != 0.0f; });

        const auto forces = in.get<uint64_t>();
        for (uint64_t k = 0; k < forces; ++k) {
            std::unique_ptr<Plugin> plugin = getPlugin(in, registry, PluginKind::Force, k);
            world.addForce(
                std::unique_ptr<ForcePlugin>(static_cast<ForcePlugin*>(plugin.release())));
        }
        const auto boundaries = in.get<uint64_t>();
        for (uint64_t k = 0; k < boundaries; ++k) {
            std::unique_ptr<Plugin> plugin = getPlugin(in, registry, PluginKind::Boundary, k);
            world.addBoundary(
                std::unique_ptr<BoundaryPlugin>(static_cast<BoundaryPlugin*>(plugin.release())));
        }

        const auto emitters = in.get<uint64_t>();
        for (uint64_t k = 0; k < emitters; ++k) {
            const EmitterId id = world.addEmitter(getEmitterDef(in));
            getEmitterClock(in, s.emitters[id.index]);
        }
        const auto drains = in.get<uint64_t>();
        for (uint64_t k = 0; k < drains; ++k) {
            DrainDef dr;
            dr.shape = getShape(in);
            dr.onlyMaterial = in.small(true, "a drain's material flag");
            dr.material = MaterialId{in.get<uint16_t>("a drain's material")};
            world.addDrain(dr);
        }
        const auto sensors = in.get<uint64_t>();
        for (uint64_t k = 0; k < sensors; ++k) {
            SensorDef se;
            se.shape = getShape(in);
            world.addSensor(se);
        }
        in.array(s.sensorReadings, "the sensor readings");
        if (s.sensorReadings.size() != s.sensors.size() * s.materials.size()) {
            corrupt("sensor readings of the wrong size");
        }
        s.time = in.get<double>();
        s.carry = in.get<double>();
        s.soundSpeed = in.get<float>();
        s.fieldGH = in.get<float>();
        s.fieldMeasured = in.small(true, "the field flag");
        s.lastMaxAccel = in.get<float>();
        s.profile = in.get<ProfileRecord>().profile();
        checkSolverState(s);
        if (s.carry > 1.0) {
            std::ostringstream text;
            text << "the carried frame time is " << s.carry << " s, more than a frame (1 s)";
            corrupt(text.str());
        }
        // Negative when the sub-steps ran ahead of the frames, by at most half a sub-step, and a
        // sub-step is at most 1/60 s (World::step).
        if (s.carry < -double(1.0f / 60.0f) / 2.0) {
            std::ostringstream text;
            text << "the carried frame time is " << s.carry
                 << " s, less than minus half the longest sub-step (-1/120 s)";
            corrupt(text.str());
        }
        if (version >= 7) {
            getGroups(in, s);
        }
        if (!in.done()) {
            corrupt("unexpected data after the last section");
        }
        return world;
    };
    try {
        return read();
    } catch (const Error& e) {
        const ErrorCode code = e.code();
        if (code == ErrorCode::BadArgument || code == ErrorCode::OutOfRange ||
            code == ErrorCode::StaleId) {
            throw Error(e.what(), ErrorCode::BadFile);
        }
        throw;
    }
}

World World::loadFile(const std::string& path, const Registry& registry, uint32_t workerCount,
                      const TaskHook& tasks) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        throw Error("World::loadFile: cannot open '" + path + "'", ErrorCode::Io);
    }
    try {
        return load(file, registry, workerCount, tasks);
    } catch (const Error& e) {
        throw Error("'" + path + "': " + e.what(), e.code());
    }
}

} // namespace fluid
