// fluid::level — level files: a whole scene (world settings, materials, blobs, plugins,
// emitters, drains, sensors, goal, Box2D bodies and joints) described in JSON. Format reference:
// docs/levels.md.
#pragma once

#include <fluid/box2d/coupling.h>
#include <fluid/error.h>
#include <fluid/gameplay.h>
#include <fluid/registry.h>
#include <fluid/task.h>
#include <fluid/world.h>

#include <box2d/box2d.h>

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fluid {

/// A level file that cannot be used: bad JSON, an unknown key, a wrong type, an out-of-range or
/// non-finite value, an unknown plugin type or preset, a bad shape, a repeated name, a name that
/// refers to nothing. `what()` reads "FILE:LINE:COLUMN: at JSON_PATH: MESSAGE" (JSON_PATH as a
/// JSON pointer, e.g. "/plugins/1/params/radius"); for the whole document (syntax errors, a
/// missing top-level key) the path is empty and `what()` reads "FILE:LINE:COLUMN: MESSAGE".
/// LINE:COLUMN point at the offending value, or at the key for an unknown or repeated key.
/// `code()` is `ErrorCode::BadFile` for malformed contents (syntax, keys, types, ranges,
/// shapes, repeated names), `ErrorCode::UnknownName` for a name nothing is registered or
/// declared under (a plugin type or parameter, a preset, a quality, a solver, a material or
/// another object the file names but does not declare) and `ErrorCode::OutOfMemory` for memory
/// that ran out making the level's particles (the `std::bad_alloc` nested).
/// Thread rule: as `fluid::Error`.
class LevelError : public Error {
public:
    /// Builds the message from its parts (line and column start at 1; 0 when unknown); `code`
    /// is the kind of failure (`ErrorCode`).
    LevelError(std::string file, uint32_t line, uint32_t column, std::string path,
               std::string message, ErrorCode code = ErrorCode::BadFile);
    /// The file name given to the loader.
    const std::string& file() const { return m_file; }
    /// Line of the offending value (unit: 1-based line number; 0 when unknown).
    uint32_t line() const { return m_line; }
    /// Column of the offending value (unit: 1-based byte column; 0 when unknown).
    uint32_t column() const { return m_column; }
    /// JSON pointer of the offending value ("" for the whole document; control characters
    /// written as `Error::printable` writes them).
    const std::string& path() const { return m_path; }
    /// What was wrong and what was expected, without the location (control characters written
    /// as `Error::printable` writes them).
    const std::string& message() const { return m_message; }

private:
    std::string m_file;
    uint32_t m_line = 0;
    uint32_t m_column = 0;
    std::string m_path;
    std::string m_message;
};

/// How a level's goal measures the fluid in its sensor.
enum class GoalMeasure : uint8_t {
    /// Particles (unit: count).
    Count,
    /// Rest area of the material over the sensor's area (unit: 1; 0.8 = 80% full).
    Fraction,
    /// Rest volume in the slab (unit: m^3).
    Volume,
};

/// Where a level's goal stands.
enum class GoalState : uint8_t {
    /// The level has no goal.
    None,
    /// Not reached yet, time left.
    Pending,
    /// The sensor holds the amount.
    Won,
    /// The time limit passed first.
    Lost,
};

/// A level's goal: a sensor, a material and an amount, optionally before a time limit.
struct LevelGoal {
    /// False when the level has no goal (the other fields are then unused).
    bool present = false;
    /// The sensor's name in the level file.
    std::string sensorName;
    /// The sensor in `Level::world`.
    SensorId sensor{};
    /// The material's name in the level file.
    std::string materialName;
    /// The material counted.
    MaterialId material{};
    /// What `amount` measures.
    GoalMeasure measure = GoalMeasure::Fraction;
    /// Amount to reach (unit: per `measure`; > 0).
    double amount = 0.0;
    /// Simulated time allowed (unit: s; 0 = no limit).
    double timeLimit = 0.0;
    /// Text for players ("Fill the cup to 80%").
    std::string description;
};

/// Collision category (`b2Filter::categoryBits`) of the fixtures of a level body declared with
/// `"fluid": false`: the level's coupling leaves them out (its `CouplingDef::categoryMask` is
/// every bit but this one). Other fixtures keep Box2D's default category, 0x0001. Box2D's
/// collisions between bodies are unchanged (every fixture's `maskBits` stays 0xFFFF).
inline constexpr uint16_t kDryFixtureCategory = 0x8000;

/// Overrides applied while loading (defined below).
struct LevelOptions;

/// A loaded level: the world, ready to step, the Box2D bodies coupled to it, and the names the
/// file gave things. Movable, not copyable (the Box2D world and its coupling move with it).
/// Thread rule: as `World`; Box2D is not thread-safe, so `physics` only on the stepping thread.
struct Level {
    /// File name given to the loader.
    std::string file;
    /// The level file's text as parsed: `save` writes it, so a save restores the level even if
    /// the file has changed or gone since.
    std::string source;
    /// The level's title and text for players.
    std::string name, description;
    /// Format version of the file (unit: 1; this loader reads 1).
    uint32_t version = 1;
    /// Frames per simulated second: `World::step(1 / frameRate)` (unit: Hz; range [1, 1000]).
    float frameRate = 60.0f;
    /// The world: materials, blobs, plugins, emitters, drains and sensors added.
    World world;
    /// Materials by name, in file order. A level read from a save lists after them the
    /// materials the game had added to the world (by their `Material::name`, or "material<k>"
    /// when that is empty or taken), so that every material the world holds has a name here.
    std::vector<std::pair<std::string, MaterialId>> materials;
    /// Emitters by name, in file order.
    std::vector<std::pair<std::string, EmitterId>> emitters;
    /// Drains by name, in file order.
    std::vector<std::pair<std::string, DrainId>> drains;
    /// Sensors by name, in file order.
    std::vector<std::pair<std::string, SensorId>> sensors;
    /// Plugins by name, in file order, with their kind and index in `World::forces()` or
    /// `World::boundaries()`.
    struct PluginEntry {
        /// Name in the file (the type when the file gives none).
        std::string name;
        /// Force or boundary.
        PluginKind kind = PluginKind::Force;
        /// Index in `World::forces()` or `World::boundaries()`.
        uint32_t index = 0;
    };
    /// See `PluginEntry`.
    std::vector<PluginEntry> plugins;
    /// The goal, if any.
    LevelGoal goal;
    /// The Box2D world of the file's `bodies`, with the level's uniform gravity (the sum of its
    /// `force.gravity` plugins, (0, 0) without one); null when the file declares no body.
    std::unique_ptr<b2World> physics;
    /// Couples `physics` to `world` (two-way: the fluid pushes the bodies, the bodies are
    /// boundaries of the fluid); null when `physics` is. Declared after `world` and `physics`,
    /// so that it is destroyed before either.
    std::unique_ptr<box2d::Coupling> coupling;
    /// Bodies by name, in file order (an unnamed body is `body<k>`, k = its index in `bodies`).
    /// Owned by `physics`.
    std::vector<std::pair<std::string, b2Body*>> bodies;
    /// Joints by name, in file order (an unnamed joint is `joint<k>`). Owned by `physics`.
    std::vector<std::pair<std::string, b2Joint*>> joints;
    /// What the loader accepted but a level author should hear about, each as
    /// "file:line:column: at /pointer: message" (for now: blobs that overlap, whose liquid
    /// starts at about twice its rest density and bursts apart). Empty for a clean file.
    std::vector<std::string> warnings;

    /// An empty level (no material; `loadLevel` and `parseLevel` make real ones).
    Level() = default;
    /// Moves the world, the Box2D world and the coupling; `other` is left empty.
    Level(Level&& other) noexcept = default;
    /// Destroys this level's coupling first (it refers to this level's world and Box2D world),
    /// then takes `other`'s contents.
    Level& operator=(Level&& other) noexcept;
    /// Destroys the coupling, then the Box2D world, then the world.
    ~Level() = default;

    /// The goal's amount the sensor held at the end of the last step (unit: per
    /// `goal.measure`: count, 1 or m^3; 0 without a goal or before the first step). Fraction =
    /// the material's rest area in the sensor over the sensor's area.
    double goalValue() const;
    /// Where the goal stands after the last step: `Won` once `goalValue() >= goal.amount`,
    /// `Lost` once `goal.timeLimit > 0` and `world.time() >= goal.timeLimit` without a win
    /// first. Both are final: the first answer other than `Pending` is kept (call this after
    /// every step, or use `step()`, so that a sensor filled for one frame is not missed).
    GoalState goalState() const;
    /// Steps the level by one frame, 1 / `frameRate` s, and updates the goal state: with bodies,
    /// `coupling->step(world, dt)` (fluid step, fluid forces on the bodies, `b2World::Step`);
    /// without, `world.step(dt)`. Throws as `World::step` and `box2d::Coupling::step`.
    void step();
    /// Steps the level by a frame of `frameDt` s (unit: s; finite, range (0, 1]), as `step`
    /// does for 1 / `frameRate`: for a game that steps by the display's frame time and draws
    /// positions between sub-steps (fluid/groups.h, `fluid::setInterpolation`). Throws as
    /// `step`, and `fluid::Error` naming frameDt out of range.
    void step(float frameDt);

    /// Destroys `body`, a body of `physics` (the file's or one the game added), with the joints
    /// attached to it, and drops them from `bodies` and `joints` (the fluid no longer meets it
    /// from the next step). Throws `fluid::Error` for a body not in `physics`, and with
    /// `ErrorCode::WrongState` during the world's own step. Stepping thread, between frames.
    void destroyBody(b2Body* body);

    /// Writes the level as it stands between frames to `out`: the level file's text, the
    /// world's snapshot (`World::save`), and with bodies the Box2D world (`box2d::savePhysics`:
    /// every body with its pose, velocities, awake state and fixtures, bodies the game added
    /// included; the revolute joints), the coupling's state (`box2d::Coupling::save`), which
    /// of them the level's names refer to, and the goal's state; a checksum closes it.
    /// `loadLevelSave` reads it back, and the level continues bit-identically, with bodies too
    /// (the Box2D save carries Box2D's contacts with their warm-starting impulses, broad phase,
    /// sweeps and sleep timers: docs/box2d.md, "Saving"), with any number of workers. Throws
    /// `fluid::Error` if the stream fails or Box2D holds a joint other than revolute. Stepping
    /// thread, between frames.
    void save(std::ostream& out) const;
    /// `save` into the file `path` (replaced once the whole save is made); errors name the
    /// file.
    void saveFile(const std::string& path) const;

private:
    friend Level readLevelSave(std::istream& in, std::string_view file, const Registry& registry,
                               const LevelOptions& options);
    // The goal state latched by goalState(): Won and Lost are final.
    mutable GoalState m_goalState = GoalState::Pending;
};

/// Overrides applied while loading (command-line flags of fluid-run, the demo's settings).
struct LevelOptions {
    /// Worker threads (unit: count; 0 = the file's `world.workers`, default 1).
    uint32_t workerCount = 0;
    /// Most particles the world may hold (unit: count; 0 = the file's `world.maxParticles`;
    /// otherwise the smaller of the two). A blob that needs more is a LevelError. Tools that
    /// load untrusted files (the fuzz target) cap memory with it.
    uint32_t maxParticles = 0;
    /// The host's thread system; when `enqueue` is set it is used instead of a pool.
    TaskHook tasks{};
};

/// Reads and builds the level in the file `path`; plugins are created from `registry`.
/// Throws `LevelError` for anything the file gets wrong (errors of the world itself, such as an
/// emitter whose rate the nozzle cannot fit, come located at the block that caused them, with
/// the world's error nested: a blob too large for memory carries its `std::bad_alloc`, which
/// `std::rethrow_if_nested` finds) and `fluid::Error` naming the file if it cannot be read. The
/// whole file is the document: a NUL byte in it is a `LevelError` naming its byte offset. Thread
/// rule: any thread; the registry is only read.
Level loadLevel(const std::string& path, const Registry& registry,
                const LevelOptions& options = {});

/// As `loadLevel`, from text in memory (all of `text`, a NUL byte in it an error as in a file);
/// `file` names it in error messages.
Level parseLevel(std::string_view text, std::string_view file, const Registry& registry,
                 const LevelOptions& options = {});

/// Reads a save written by `Level::save`: the level is rebuilt from the saved file text (with
/// `options`; `workerCount` 0 keeps the saved world's count), then the world, Box2D world and
/// coupling state are restored. `registry` must know the world's plugin types (the coupling's
/// own, "box2d.bodies", is added here). The header (magic and version) is checked from the
/// first 12 bytes, before the rest is read. The world must hold what the level text declares,
/// at the ids the text gives them: each material (by name), force and boundary plugin (by
/// type), emitter, drain and sensor; what the game added after loading (materials, plugins,
/// ...) is kept. Throws `fluid::Error` "level save 'FILE': ..." naming `file` for a save that is
/// not one, truncated or corrupt (checksum), of another version, whose world lacks or differs
/// from what its level text declares ("its level file declares sensor 'cup' (0), but the world
/// holds 0 sensors"), or whose parts fail to load, naming the part and its field ("the level
/// file: ...", "the world: snapshot: ...", "the Box2D world: box2d save: ...", "the coupling:
/// coupling save: body 2 debt x = ... is not finite or out of [...]"). Thread rule: any
/// thread; the registry is only read.
Level readLevelSave(std::istream& in, std::string_view file, const Registry& registry,
                    const LevelOptions& options = {});

/// `readLevelSave` from the file `path`.
Level loadLevelSave(const std::string& path, const Registry& registry,
                    const LevelOptions& options = {});

} // namespace fluid
