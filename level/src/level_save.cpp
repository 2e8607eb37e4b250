// fluid::level — saving and restoring a level between frames (Level::save, readLevelSave).
#include <fluid/box2d/physics_save.h>
#include <fluid/internal/binary.h>
#include <fluid/level.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace fluid {

namespace {

constexpr char kMagic[8] = {'F', 'L', 'U', 'I', 'D', 'L', 'V', 'L'};
constexpr uint32_t kVersion = 1;
// A name that refers to nothing any more (the game destroyed the body or joint).
constexpr uint32_t kGone = 0xFFFFFFFFu;

using Parts = internal::ByteReader;

// Where a save's errors start: "level save '<file>'".
std::string saveName(std::string_view file) {
    return "level save '" + std::string(file) + "'";
}

} // namespace

void Level::save(std::ostream& out) const {
    internal::ByteWriter w;
    w.bytes.assign(kMagic, sizeof(kMagic));
    w.put<uint32_t>(kVersion);
    w.string(file);
    w.string(source);
    w.put<uint32_t>(uint32_t(m_goalState));
    std::ostringstream worldBytes;
    world.save(worldBytes);
    w.string(worldBytes.str());
    w.put<uint32_t>(physics ? 1 : 0);
    if (physics) {
        std::ostringstream physicsBytes, couplingBytes;
        box2d::savePhysics(*physics, physicsBytes);
        coupling->save(couplingBytes);
        w.string(physicsBytes.str());
        w.string(couplingBytes.str());
        // The level's names by position in Box2D's lists.
        std::unordered_map<const b2Body*, uint32_t> bodyIndex; // lookup only
        for (const b2Body* b = physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
            bodyIndex.emplace(b, uint32_t(bodyIndex.size()));
        }
        std::unordered_map<const b2Joint*, uint32_t> jointIndex; // lookup only
        for (const b2Joint* j = physics->GetJointList(); j != nullptr; j = j->GetNext()) {
            jointIndex.emplace(j, uint32_t(jointIndex.size()));
        }
        w.put<uint32_t>(uint32_t(bodies.size()));
        for (const auto& [bodyName, body] : bodies) {
            const auto found = bodyIndex.find(body);
            w.put<uint32_t>(found != bodyIndex.end() ? found->second : kGone);
        }
        w.put<uint32_t>(uint32_t(joints.size()));
        for (const auto& [jointName, joint] : joints) {
            const auto found = jointIndex.find(joint);
            w.put<uint32_t>(found != jointIndex.end() ? found->second : kGone);
        }
    }
    w.put(internal::fnv1a(w.bytes));
    out.write(w.bytes.data(), std::streamsize(w.bytes.size()));
    if (!out) {
        throw Error("Level::save: the stream failed while writing the save of '" + file + "'",
                    ErrorCode::Io);
    }
}

void Level::saveFile(const std::string& path) const {
    std::ostringstream bytes;
    save(bytes);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) {
        throw Error("Level::saveFile: cannot open '" + path + "' for writing", ErrorCode::Io);
    }
    const std::string data = bytes.str();
    out.write(data.data(), std::streamsize(data.size()));
    out.close();
    if (!out) {
        throw Error("Level::saveFile: writing '" + path + "' failed", ErrorCode::Io);
    }
}

namespace {

// The whole save, read once its header holds: the magic and version are checked from the first
// 12 bytes, before the body is read (a huge file of another version is refused at once).
std::string readSave(std::istream& in, const Parts& check) {
    std::string raw(sizeof(kMagic) + sizeof(uint32_t), '\0');
    in.read(raw.data(), std::streamsize(raw.size()));
    raw.resize(std::size_t(in.gcount()));
    if (raw.size() < sizeof(kMagic) || std::memcmp(raw.data(), kMagic, sizeof(kMagic)) != 0) {
        check.fail("not a level save (no FLUIDLVL header)");
    }
    if (raw.size() < sizeof(kMagic) + sizeof(uint32_t)) {
        check.fail("truncated (" + std::to_string(raw.size()) + " bytes)");
    }
    uint32_t version = 0;
    std::memcpy(&version, raw.data() + sizeof(kMagic), sizeof(version));
    if (version != kVersion) {
        check.fail("format version " + std::to_string(version) +
                   " is not supported; this fluid reads version " + std::to_string(kVersion));
    }
    char buffer[65536];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) {
        raw.append(buffer, std::size_t(in.gcount()));
    }
    if (raw.size() < sizeof(kMagic) + sizeof(uint32_t) + sizeof(uint64_t)) {
        check.fail("truncated (" + std::to_string(raw.size()) + " bytes)");
    }
    return raw;
}

// Fails unless the world holds, at the ids its level file gave them, everything the file
// declares: materials by name, forces and boundaries by type (`parsed` is the world the level
// file builds), emitters, drains and sensors. The game may have added more after loading (the
// demo adds its materials and pointer force): those are kept.
void checkDeclared(const Level& level, const World& parsed, const World& world,
                   const Parts& parts) {
    const auto missing = [&](const std::string& what, const std::string& name, uint32_t id,
                             uint32_t held, const std::string& plural) {
        parts.fail("its level file declares " + what + " '" + name + "' (" + std::to_string(id) +
                   "), but the world holds " + std::to_string(held) + " " + plural);
    };
    for (const auto& [name, id] : level.materials) {
        if (id.index >= world.materialCount()) {
            missing("material", name, id.index, world.materialCount(), "materials");
        }
        const std::string& held = world.material(world.adopt(id)).name;
        if (held != name) {
            parts.fail("its level file declares material '" + name + "' (" +
                       std::to_string(id.index) + "), but the world's material " +
                       std::to_string(id.index) + " is '" + held + "'");
        }
    }
    for (const Level::PluginEntry& entry : level.plugins) {
        const bool force = entry.kind == PluginKind::Force;
        const auto type = [&](const World& w) -> std::string_view {
            return force ? w.forces()[entry.index]->type() : w.boundaries()[entry.index]->type();
        };
        const std::size_t held = force ? world.forces().size() : world.boundaries().size();
        const std::string what = force ? "force" : "boundary";
        if (entry.index >= held) {
            missing(what, entry.name, entry.index, uint32_t(held),
                    force ? "forces" : "boundaries");
        }
        if (type(world) != type(parsed)) {
            parts.fail("its level file declares " + what + " '" + entry.name + "' (" +
                       std::to_string(entry.index) + ") of type '" + std::string(type(parsed)) +
                       "', but the world's " + what + " " + std::to_string(entry.index) +
                       " is of type '" + std::string(type(world)) + "'");
        }
    }
    const auto ids = [&](const auto& named, uint32_t held, const char* what, const char* plural) {
        for (const auto& [name, id] : named) {
            if (id.index >= held) {
                missing(what, name, id.index, held, plural);
            }
        }
    };
    ids(level.emitters, world.emitterCount(), "emitter", "emitters");
    ids(level.drains, world.drainCount(), "drain", "drains");
    ids(level.sensors, world.sensorCount(), "sensor", "sensors");
}

// Materials the game added to the world after loading the level (beyond the file's), named as
// the world names them ("material<k>" when that name is empty or taken): `Level::materials`
// lists every material the world holds, so tools see them all.
void nameAddedMaterials(Level& level) {
    for (uint32_t k = uint32_t(level.materials.size()); k < level.world.materialCount(); ++k) {
        const MaterialId id = level.world.adopt(MaterialId{uint16_t(k)});
        const auto taken = [&](const std::string& name) {
            return name.empty() ||
                   std::any_of(level.materials.begin(), level.materials.end(),
                               [&](const auto& entry) { return entry.first == name; });
        };
        std::string name = level.world.material(id).name;
        for (uint32_t n = 0; taken(name); ++n) {
            name = "material" + std::to_string(k);
            if (n > 0) {
                name += '_';
                name += std::to_string(n);
            }
        }
        level.materials.emplace_back(name, id);
    }
}

} // namespace

Level readLevelSave(std::istream& in, std::string_view file, const Registry& registry,
                    const LevelOptions& options) {
    const Parts check(std::string_view(), saveName(file));
    const std::string raw = readSave(in, check);
    const std::string_view data = std::string_view(raw).substr(0, raw.size() - sizeof(uint64_t));
    uint64_t sum = 0;
    std::memcpy(&sum, raw.data() + data.size(), sizeof(sum));
    if (sum != internal::fnv1a(data)) {
        check.fail("corrupt or truncated (checksum mismatch)");
    }
    Parts parts(data.substr(sizeof(kMagic) + sizeof(uint32_t)), saveName(file));
    const std::string levelFile(parts.bytes("the level file name"));
    const std::string_view source = parts.bytes("the level file text");
    const uint32_t goalState = parts.get<uint32_t>("the goal state");
    if (goalState > uint32_t(GoalState::Lost)) {
        parts.fail("goal state " + std::to_string(goalState) + " is not one");
    }
    const std::string_view worldBytes = parts.bytes("the world");
    const uint32_t hasPhysics = parts.get<uint32_t>("the Box2D flag");

    // The part's own error follows the save's name.
    const auto located = [&](const char* part, const auto& load) {
        try {
            return load();
        } catch (const Error& e) {
            // The part's contents are the save's fault, unless memory ran out or a name is
            // unknown (a plugin type not registered).
            const ErrorCode code = e.code();
            parts.fail(std::string(part) + ": " + e.what(),
                       code == ErrorCode::OutOfMemory || code == ErrorCode::UnknownName
                           ? code
                           : ErrorCode::BadFile);
        }
    };
    // Everything but the state comes from the level file, as the game loaded it.
    Level level = located("the level file",
                          [&] { return parseLevel(source, levelFile, registry, options); });
    if ((hasPhysics == 1) != (level.physics != nullptr)) {
        parts.fail(hasPhysics == 1 ? "holds a Box2D world, but its level file declares no body"
                                   : "holds no Box2D world, but its level file declares bodies");
    }
    const box2d::CouplingDef couplingDef =
        level.coupling ? level.coupling->def() : box2d::CouplingDef{};
    std::vector<std::string> bodyNames, jointNames;
    for (const auto& entry : level.bodies) {
        bodyNames.push_back(entry.first);
    }
    for (const auto& entry : level.joints) {
        jointNames.push_back(entry.first);
    }
    level.coupling.reset();
    level.joints.clear();
    level.bodies.clear();
    level.physics.reset();

    Registry withCoupling = registry;
    if (withCoupling.find("box2d.bodies") == nullptr) {
        box2d::registerCouplingPlugin(withCoupling);
    }
    World world = located("the world", [&] {
        std::istringstream s{std::string(worldBytes)};
        return World::load(s, withCoupling, options.workerCount, options.tasks);
    });
    checkDeclared(level, level.world, world, parts);
    level.world = std::move(world);
    // The ids the level file gave are the loaded world's now (the same indices: checkDeclared).
    for (auto& entry : level.materials) {
        entry.second = level.world.adopt(entry.second);
    }
    for (auto& entry : level.emitters) {
        entry.second = level.world.adopt(entry.second);
    }
    for (auto& entry : level.drains) {
        entry.second = level.world.adopt(entry.second);
    }
    for (auto& entry : level.sensors) {
        entry.second = level.world.adopt(entry.second);
    }
    level.goal.sensor = level.world.adopt(level.goal.sensor);
    level.goal.material = level.world.adopt(level.goal.material);
    nameAddedMaterials(level);
    level.m_goalState = GoalState(goalState);
    if (hasPhysics == 1) {
        const std::string_view physicsBytes = parts.bytes("the Box2D world");
        const std::string_view couplingBytes = parts.bytes("the coupling");
        level.physics = located("the Box2D world", [&] {
            std::istringstream s{std::string(physicsBytes)};
            return box2d::loadPhysics(s);
        });
        std::vector<b2Body*> bodyList;
        for (b2Body* b = level.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
            bodyList.push_back(b);
        }
        std::vector<b2Joint*> jointList;
        for (b2Joint* j = level.physics->GetJointList(); j != nullptr; j = j->GetNext()) {
            jointList.push_back(j);
        }
        const auto names = [&](const char* what, const std::vector<std::string>& fileNames,
                               const auto& list, auto& out) {
            const uint32_t count = parts.get<uint32_t>(what);
            if (count != fileNames.size()) {
                parts.fail(std::string("names ") + std::to_string(count) + " " + what +
                           "; its level file declares " + std::to_string(fileNames.size()));
            }
            for (uint32_t k = 0; k < count; ++k) {
                const uint32_t index = parts.get<uint32_t>(what);
                if (index == kGone) {
                    continue; // destroyed by the game before the save
                }
                if (index >= list.size()) {
                    parts.fail(std::string(what) + " '" + fileNames[k] + "' is number " +
                               std::to_string(index) + " of " + std::to_string(list.size()));
                }
                out.emplace_back(fileNames[k], list[index]);
            }
        };
        names("bodies", bodyNames, bodyList, level.bodies);
        names("joints", jointNames, jointList, level.joints);
        level.coupling = located("the coupling", [&] {
            auto coupling =
                std::make_unique<box2d::Coupling>(level.world, *level.physics, couplingDef);
            std::istringstream s{std::string(couplingBytes)};
            coupling->load(s);
            return coupling;
        });
    } else if (hasPhysics != 0) {
        parts.fail("Box2D flag " + std::to_string(hasPhysics) + " is not 0 or 1");
    }
    if (!parts.done()) {
        parts.fail("bytes left over after the last part");
    }
    return level;
}

Level loadLevelSave(const std::string& path, const Registry& registry,
                    const LevelOptions& options) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error("loadLevelSave: cannot open '" + path + "'", ErrorCode::Io);
    }
    return readLevelSave(in, path, registry, options);
}

} // namespace fluid
