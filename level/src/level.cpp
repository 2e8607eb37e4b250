// fluid::level — the level format (docs/levels.md): reads a JSON level strictly and builds its
// world. Every problem is a LevelError located at the value (or key) that caused it.
#include "bodies.h"
#include "json_positions.h"
#include "names.h"

#include <fluid/groups.h>
#include <fluid/level.h>
#include <fluid/plugins/kinematic_shape.h>
#include <fluid/material.h>
#include <fluid/shape.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <system_error>
#include <unordered_map>

namespace fluid {

namespace {
std::string composeLevelMessage(const std::string& file, uint32_t line, uint32_t column,
                                const std::string& path, const std::string& message) {
    std::string out = file;
    if (line > 0) {
        out += ':' + std::to_string(line) + ':' + std::to_string(column);
    }
    out += ": ";
    if (!path.empty()) {
        out += "at " + path + ": ";
    }
    return out + message;
}
} // namespace

LevelError::LevelError(std::string file, uint32_t line, uint32_t column, std::string path,
                       std::string message, ErrorCode code)
    : Error(composeLevelMessage(file, line, column, path, message), code), m_file(std::move(file)),
      m_line(line), m_column(column), m_path(printable(path)), m_message(printable(message)) {}

namespace {

// The goal's amounts, as a goal names them ("fraction": 0.8): the one table of them, in the
// order messages list them.
constexpr EnumName<GoalMeasure> kGoalMeasureNames[] = {
    {GoalMeasure::Fraction, "fraction"},
    {GoalMeasure::Count, "count"},
    {GoalMeasure::Volume, "volume"},
};

using detail::childPointer;
using detail::formatNumber;
using detail::joined;
using detail::Json;
using detail::JsonDocument;
using detail::located;
using detail::NameTable;
using detail::ObjectReader;
using detail::Range;

/// The format version this loader reads.
constexpr uint64_t kVersion = 1;

// Ranges of the format (docs/levels.md lists them). World-space coordinates are bounded so
// that lattice sizes and float conversions stay meaningful.
constexpr Range kCoordinate{-1e5, 1e5, "m"};
constexpr Range kSize{0.0, 1e5, "m", true};
constexpr Range kVelocity{-1e3, 1e3, "m/s"};
constexpr Range kLifetime{0.0, 1e6, "s"};
constexpr Range kStructure{0.0, 1.0, "1"};
constexpr Range kLatticeAngle{-6.2832, 6.2832, "rad"};
constexpr Range kFrameRate{1.0, 1000.0, "Hz"};
// A blob's particle closer than this many lattice spacings to an earlier blob's lies inside
// that blob (warnOverlaps).
constexpr double kOverlapReach = 0.8;

// A field's range as the loader checks a file's numbers.
template <class Def> Range fieldRange(const Field<Def>& f) {
    return Range{f.lo, f.hi, f.unit, f.openLow};
}

// Appends the keys of `fields` to `names`.
template <class Def>
void addNames(std::vector<std::string_view>& names, std::span<const Field<Def>> fields) {
    for (const Field<Def>& f : fields) {
        names.push_back(f.name);
    }
}

// Reads the fields `fields` of `def` from `o`, each keeping `def`'s value when the file leaves
// it out (whole numbers must be whole).
template <class Def>
void readFields(const ObjectReader& o, std::span<const Field<Def>> fields, Def& def) {
    for (const Field<Def>& f : fields) {
        f.set(def, f.whole != nullptr
                       ? double(o.integer(f.name, fieldRange(f), uint64_t(f.get(def))))
                       : o.number(f.name, fieldRange(f), f.get(def)));
    }
}

class LevelReader {
public:
    LevelReader(const JsonDocument& doc, const Registry& registry, const LevelOptions& options,
                Level& level)
        : m_doc(doc), m_registry(registry), m_options(options), m_level(level) {}

    void read() {
        const ObjectReader root(m_doc, m_doc.root(), "", "a level");
        root.allowOnly({"version", "name", "description", "world", "materials", "blobs", "plugins",
                        "emitters", "drains", "sensors", "goal", "bodies", "joints", "coupling"});
        root.required("version", "the format version (1)");
        const uint64_t v = root.integer("version", {1.0, 1e9, "1"}, kVersion);
        if (v != kVersion) {
            root.failAt("version", "unsupported version " + std::to_string(v) +
                                       "; this loader reads version " + std::to_string(kVersion));
        }
        m_level.version = uint32_t(v);
        m_level.name = root.string("name", "");
        if (const std::string problem = internal::nameProblem(m_level.name); !problem.empty()) {
            root.failAt("name", problem);
        }
        m_level.description = root.string("description", "");

        readWorld(root);
        readMaterials(root);
        readPlugins(root);
        readEmitters(root);
        readDrains(root);
        readSensors(root);
        readGoal(root);
        // The coupling's boundary plugin joins after the file's containers (see
        // box2d::Coupling), and bodies' densities read the finished world's materials.
        detail::readBodies(m_doc, root, m_level);
        // Last: blobs leave out the lattice points inside every solid, bodies included.
        readBlobs(root);
    }

private:
    // ---- world ---------------------------------------------------------------------------
    void readWorld(const ObjectReader& root) {
        WorldDef def;
        std::optional<glm::dvec2> gravity;
        std::string gravityPointer;
        if (const Json* value = root.find("world")) {
            const ObjectReader w(m_doc, *value, root.pointer("world"), "the world settings");
            std::vector<std::string_view> allowed{"gravity", "frameRate", "solver", "quality"};
            addNames(allowed, positionBasedFields());
            allowed.insert(allowed.end(),
                           {"equationOfState", "soundSpeed", "workers", "colourMixing"});
            addNames(allowed, worldFields());
            w.allowOnly(allowed);
            if (w.has("gravity")) {
                gravityPointer = w.pointer("gravity");
                gravity = readGravity(w);
            }
            m_level.frameRate = float(w.number("frameRate", kFrameRate, 60.0));
            const std::string solver = w.string("solver", std::string(solverName(def.solver)));
            if (const std::optional<Solver> named = solverFromName(solver)) {
                def.solver = *named;
            } else {
                w.failAt("solver",
                         "unknown solver " + internal::quoted(solver) +
                             "; known: " + namesIn(kSolverNames, ", "),
                         ErrorCode::UnknownName);
            }
            // A named preset first; explicit substeps, iterations and viscosityInterval
            // override its fields.
            const std::string quality = w.string("quality", "");
            if (const std::optional<Quality> named = qualityFromName(quality)) {
                def.positionBased = positionBasedPreset(*named);
            } else if (!quality.empty()) {
                w.failAt("quality",
                         "unknown quality " + internal::quoted(quality) +
                             "; known: " + namesIn(kQualityNames, ", "),
                         ErrorCode::UnknownName);
            }
            readFields(w, positionBasedFields(), def.positionBased);
            const std::string eos = w.string(
                "equationOfState", std::string(equationOfStateName(EquationOfState::Tait)));
            if (const std::optional<EquationOfState> named = equationOfStateFromName(eos)) {
                def.equationOfState = *named;
            } else {
                w.failAt("equationOfState",
                         "unknown equation of state " + internal::quoted(eos) +
                             "; known: " + namesIn(kEquationOfStateNames, ", "),
                         ErrorCode::UnknownName);
            }
            const double c = w.number("soundSpeed", {0, 1e4, "m/s"}, 0.0);
            if (c > 0.0 && c < 0.1) {
                w.failAt("soundSpeed", formatNumber(c) +
                                           " is out of range: 0 (derive from the scene) or "
                                           "[0.1, 10000] (unit: m/s)");
            }
            def.soundSpeed = float(c);
            readFields(w, worldFields(), def);
            def.workerCount = uint32_t(w.integer("workers", {1, 256, "count"}, 1));
            // Colour mixing between coloured blobs (fluid/groups.h), set once the world exists.
            colourMixing = float(w.number("colourMixing", {0, 1000, "1/s"}, 0.0));
        }
        if (m_options.workerCount > 0) {
            def.workerCount = m_options.workerCount;
        }
        def.tasks = m_options.tasks;
        if (m_options.maxParticles > 0) {
            def.maxParticles = std::min(def.maxParticles, m_options.maxParticles);
        }
        m_level.world = located(m_doc, root.has("world") ? root.pointer("world") : "",
                                [&] { return World(def); });
        setColourMixing(m_level.world, colourMixing);
        if (gravity) {
            // force.gravity is the world's first force, so plugins listed later act after it.
            const std::array<ParamValue, 2> g{{{"gx", gravity->x}, {"gy", gravity->y}}};
            located(m_doc, gravityPointer,
                    [&] { m_level.world.addForce(m_registry.createForce("force.gravity", g)); });
            addPluginName("gravity", gravityPointer, PluginKind::Force, 0);
        }
    }

    glm::dvec2 readGravity(const ObjectReader& w) const {
        const std::string at = w.pointer("gravity");
        const PluginInfo* info = m_registry.find("force.gravity");
        if (info == nullptr || info->kind != PluginKind::Force) {
            m_doc.fail(at, "world gravity needs the plugin type 'force.gravity', which the "
                           "registry does not have");
        }
        Range axis[2] = {{-1e3, 1e3, "m/s^2"}, {-1e3, 1e3, "m/s^2"}};
        for (const ParamDecl& decl : info->params) {
            if (decl.name == "gx" || decl.name == "gy") {
                axis[decl.name == "gy"] = Range{decl.minValue, decl.maxValue, decl.unit};
            }
        }
        const Json& value = *w.find("gravity");
        if (!value.is_array() || value.size() != 2) {
            m_doc.fail(at, "expected a vector [gx, gy] of two numbers (unit: m/s^2), got " +
                               (value.is_array() ? "an array of " + std::to_string(value.size())
                                                 : detail::describeType(value)));
        }
        return {detail::readNumber(m_doc, value[0], childPointer(at, std::size_t(0)), axis[0]),
                detail::readNumber(m_doc, value[1], childPointer(at, std::size_t(1)), axis[1])};
    }

    // ---- materials -----------------------------------------------------------------------
    void readMaterials(const ObjectReader& root) {
        const Json* list = root.array("materials", "materials");
        if (list == nullptr || list->empty()) {
            if (list == nullptr) {
                root.fail("missing key 'materials'; expected an array of at least one material");
            }
            root.failAt("materials", "expected at least one material, got an empty array");
        }
        for (std::size_t i = 0; i < list->size(); ++i) {
            const std::string at = childPointer(root.pointer("materials"), i);
            const ObjectReader m(m_doc, (*list)[i], at, "a material");
            std::vector<std::string_view> allowed{"name", "preset"};
            addNames(allowed, materialFields());
            m.allowOnly(allowed);
            const std::string name = requiredName(m, "material");
            const std::string preset = m.string("preset", "water");
            Material material;
            if (preset == "water") {
                material = water();
            } else if (preset == "yoghurt") {
                material = yoghurt();
            } else if (preset == "seed_yoghurt") {
                material = seedYoghurt();
            } else {
                m.failAt("preset",
                         "unknown preset " + internal::quoted(preset) +
                             "; known: water, yoghurt, seed_yoghurt",
                         ErrorCode::UnknownName);
            }
            material.name = name;
            readFields(m, materialFields(), material);
            const MaterialId id =
                located(m_doc, at, [&] { return m_level.world.addMaterial(material); });
            m_materials.add(m_doc, name, m.pointer("name"), id);
            m_level.materials.emplace_back(name, id);
        }
    }

    // ---- plugins -------------------------------------------------------------------------
    void readPlugins(const ObjectReader& root) {
        const Json* list = root.array("plugins", "plugins");
        for (std::size_t i = 0; list != nullptr && i < list->size(); ++i) {
            const std::string at = childPointer(root.pointer("plugins"), i);
            const ObjectReader p(m_doc, (*list)[i], at, "a plugin");
            p.allowOnly({"type", "name", "params", "contacts"});
            const std::string type = p.requiredString("type", "a plugin type (a string)");
            const PluginInfo* info = m_registry.find(type);
            if (info == nullptr) {
                std::vector<std::string> known;
                for (const PluginInfo& k : m_registry.types()) {
                    known.push_back(k.type);
                }
                p.failAt("type",
                         "unknown plugin type " + internal::quoted(type) +
                             "; known: " + joined(known),
                         ErrorCode::UnknownName);
            }
            const bool named = p.has("name");
            const std::string name = named ? requiredName(p, "plugin") : type;
            std::unique_ptr<ForcePlugin> force;
            std::unique_ptr<BoundaryPlugin> boundary;
            located(m_doc, at, [&] {
                if (info->kind == PluginKind::Force) {
                    force = m_registry.createForce(type);
                } else {
                    boundary = m_registry.createBoundary(type);
                }
            });
            Plugin& plugin = force ? static_cast<Plugin&>(*force) : *boundary;
            if (const Json* params = p.find("params")) {
                const ObjectReader reader(m_doc, *params, p.pointer("params"),
                                          "the plugin's parameters");
                readParams(*info, plugin, reader);
                requirePoints(*info, p, &reader);
            } else {
                requirePoints(*info, p, nullptr);
            }
            // Values that pass one by one but not together (a box with minX >= maxX): a load
            // error at the parameters, not a step that throws later.
            located(m_doc, p.has("params") ? p.pointer("params") : at,
                    [&] { plugin.checkParams(); });
            // Contact events (fluid/contacts.h): a shape asks for them.
            if (p.boolean("contacts", false)) {
                auto* shape = dynamic_cast<KinematicShape*>(boundary.get());
                if (shape == nullptr) {
                    p.failAt("contacts", "contact events are reported for the shapes "
                                         "boundary.polygon, boundary.chain and boundary.circle; " +
                                             internal::quoted(type) + " has none");
                }
                shape->setContactEvents(true);
            }
            uint32_t index = 0;
            located(m_doc, at, [&] {
                if (force) {
                    index = uint32_t(m_level.world.forces().size());
                    m_level.world.addForce(std::move(force));
                } else {
                    index = uint32_t(m_level.world.boundaries().size());
                    m_level.world.addBoundary(std::move(boundary));
                }
            });
            if (named) {
                addPluginName(name, p.pointer("name"), info->kind, index);
            } else {
                m_level.plugins.push_back({name, info->kind, index});
            }
        }
    }

    // Parameters are checked against the registry's declarations (Number: a value in range;
    // Points: a list of [x, y]), so every plugin type works without special cases. They are
    // set in declaration order, whatever order the file lists them in.
    void readParams(const PluginInfo& info, Plugin& plugin, const ObjectReader& params) const {
        std::vector<std::string_view> known;
        for (const ParamDecl& decl : info.params) {
            known.push_back(decl.name);
        }
        if (const std::optional<std::string> unknown = params.firstUnknownKey(known)) {
            std::string list;
            for (const std::string_view k : known) {
                list += (list.empty() ? "" : ", ") + std::string(k);
            }
            m_doc.failAtKey(params.pointer(*unknown),
                            "unknown parameter " + internal::quoted(*unknown) + " of plugin '" +
                                info.type + "'; known: " + (list.empty() ? "(none)" : list),
                            ErrorCode::UnknownName);
        }
        for (const ParamDecl& decl : info.params) {
            const Json* value = params.find(decl.name);
            if (value == nullptr) {
                continue;
            }
            setParam(plugin, decl, *value, params.pointer(decl.name));
        }
    }

    // A plugin starts with no points: a point list whose declaration needs some must be given.
    void requirePoints(const PluginInfo& info, const ObjectReader& p,
                       const ObjectReader* params) const {
        for (const ParamDecl& decl : info.params) {
            if (decl.type == ParamType::Points && decl.minValue > 0.0 &&
                (params == nullptr || !params->has(decl.name))) {
                const std::string what =
                    "missing parameter '" + std::string(decl.name) + "' of plugin '" + info.type +
                    "'; expected a list of " + formatNumber(decl.minValue) + " to " +
                    formatNumber(decl.maxValue) +
                    " points [[x, y], ...] (unit: " + std::string(decl.unit) + ")";
                if (params == nullptr) {
                    p.fail(what);
                }
                params->fail(what);
            }
        }
    }

    void setParam(Plugin& plugin, const ParamDecl& decl, const Json& value,
                  const std::string& at) const {
        if (decl.type == ParamType::Number) {
            const double v =
                detail::readNumber(m_doc, value, at, {decl.minValue, decl.maxValue, decl.unit});
            located(m_doc, at, [&] { plugin.setParam(decl.name, v); });
            return;
        }
        // Counts are declared as doubles (by plugin libraries too): clamp before converting.
        const auto clampCount = [](double c) { return c >= 0.0 ? std::min(c, 1e15) : 0.0; };
        const double lo = std::ceil(clampCount(decl.minValue));
        const double hi = std::max(std::floor(clampCount(decl.maxValue)), lo);
        const std::vector<glm::vec2> points =
            detail::readPoints(m_doc, value, at, kCoordinate, std::size_t(lo), std::size_t(hi));
        located(m_doc, at, [&] { plugin.setPoints(decl.name, points); });
    }

    void addPluginName(const std::string& name, const std::string& pointer, PluginKind kind,
                       uint32_t index) {
        m_pluginNames.add(m_doc, name, pointer, index);
        m_level.plugins.push_back({name, kind, index});
    }

    // ---- shapes and blobs ----------------------------------------------------------------
    // Reads "shape" and its fields; `common` are the other keys the object may have.
    Shape readShape(const ObjectReader& o, std::vector<std::string_view> common) const {
        const std::string type = o.requiredString("shape", "a shape: box, circle or polygon");
        Shape shape;
        common.push_back("shape");
        if (type == "box") {
            common.insert(common.end(), {"min", "max"});
            o.allowOnly(common);
            const glm::vec2 lo = o.requiredPoint("min", kCoordinate);
            const glm::vec2 hi = o.requiredPoint("max", kCoordinate);
            if (!(hi.x > lo.x && hi.y > lo.y)) {
                o.failAt("max", "expected max > min on both axes, got min [" + formatNumber(lo.x) +
                                    ", " + formatNumber(lo.y) + "], max [" + formatNumber(hi.x) +
                                    ", " + formatNumber(hi.y) + "]");
            }
            shape = Shape::box(lo, hi);
        } else if (type == "circle") {
            common.insert(common.end(), {"center", "radius"});
            o.allowOnly(common);
            shape = Shape::circle(o.requiredPoint("center", kCoordinate),
                                  float(o.requiredNumber("radius", kSize)));
        } else if (type == "polygon") {
            common.push_back("vertices");
            o.allowOnly(common);
            // The core's cap (fluid::kMaxPolygonVertices), checked before the points are read.
            shape =
                Shape::polygon(o.requiredPoints("vertices", kCoordinate, 3, kMaxPolygonVertices));
        } else {
            o.failAt("shape",
                     "unknown shape " + internal::quoted(type) + "; known: box, circle, polygon",
                     ErrorCode::UnknownName);
        }
        // Crossing edges, zero area, sizes lost in the float conversion: the core's check,
        // re-located at the field that holds the geometry.
        const std::string_view field = shape.type == ShapeType::Polygon  ? "vertices"
                                       : shape.type == ShapeType::Circle ? "radius"
                                                                         : "max";
        if (const std::string problem = shapeProblem(shape); !problem.empty()) {
            o.failAt(field, problem);
        }
        return shape;
    }

    // "#rrggbb" or "#rrggbbaa" (alpha not 0), or nothing.
    static std::optional<Colour> parseColour(const std::string& text) {
        if ((text.size() != 7 && text.size() != 9) || text[0] != '#') {
            return std::nullopt;
        }
        uint8_t bytes[4] = {0, 0, 0, 255};
        for (std::size_t k = 1; k < text.size(); k += 2) {
            uint32_t v = 0;
            for (std::size_t d = k; d < k + 2; ++d) {
                const char ch = text[d];
                const int digit = ch >= '0' && ch <= '9'   ? ch - '0'
                                  : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10
                                  : ch >= 'A' && ch <= 'F' ? ch - 'A' + 10
                                                           : -1;
                if (digit < 0) {
                    return std::nullopt;
                }
                v = v * 16 + uint32_t(digit);
            }
            bytes[(k - 1) / 2] = uint8_t(v);
        }
        if (bytes[3] == 0) {
            return std::nullopt;
        }
        return Colour{bytes[0], bytes[1], bytes[2], bytes[3]};
    }

    void readBlobs(const ObjectReader& root) {
        const Json* list = root.array("blobs", "blobs");
        for (std::size_t i = 0; list != nullptr && i < list->size(); ++i) {
            const std::string at = childPointer(root.pointer("blobs"), i);
            const ObjectReader b(m_doc, (*list)[i], at, "a blob");
            const Shape shape =
                readShape(b, {"material", "velocity", "lifetime", "structure", "latticeAngle",
                              "colour"});
            BlobDef blob;
            blob.shape = shape;
            blob.material =
                m_materials.find(m_doc, b.requiredString("material", "the name of a material"),
                                 b.pointer("material"));
            blob.velocity = b.point("velocity", kVelocity, {0.0f, 0.0f});
            blob.lifetime = float(b.number("lifetime", kLifetime, 0.0));
            blob.structure = float(b.number("structure", kStructure, 0.0));
            blob.latticeAngle = float(b.number("latticeAngle", kLatticeAngle, 0.0));
            // "colour": "#rrggbb" or "#rrggbbaa" (sRGB): the blob is a group of that colour.
            if (b.has("colour")) {
                const std::string text = b.string("colour", "");
                const std::optional<Colour> c = parseColour(text);
                if (!c) {
                    b.failAt("colour", "expected \"#rrggbb\" or \"#rrggbbaa\" (hexadecimal "
                                       "sRGB, alpha not 00), got " + internal::quoted(text));
                }
                blob.group = createGroup(m_level.world, GroupDef{0, *c});
            }
            const double lattice = checkBlobSize(b, shape, blob.material);
            const uint32_t first = m_level.world.particleCount();
            uint32_t inside = 0;
            uint32_t added = 0;
            try {
                added = located(m_doc, at, [&] { return m_level.world.spawnBlob(blob, &inside); });
            } catch (const std::bad_alloc&) {
                std::throw_with_nested(
                    m_doc.errorAt(at, detail::outOfMemoryText("the blob's", lattice, first),
                                  ErrorCode::OutOfMemory));
            }
            if (added == 0 && inside > 0) {
                b.fail("the blob holds no particle: all of its " + std::to_string(inside) +
                       " lattice points lie inside solids (plugins or bodies) or outside the "
                       "container");
            }
            if (inside > 0) {
                m_level.warnings.push_back(m_doc.locatedText(
                    at, std::to_string(inside) + " of the blob's " +
                            std::to_string(inside + added) +
                            " lattice points lie inside solids (plugins or bodies) or outside "
                            "the container and were left out"));
            }
            if (added == 0) {
                b.fail("the blob holds no particle: it is smaller than the material's lattice "
                       "spacing " +
                       formatNumber(m_level.world.spacing(blob.material)) + " m");
            }
            warnOverlaps(at, i, first, m_level.world.spacing(blob.material));
        }
    }

    // Blobs that overlap start their liquid at about twice its rest density: it bursts apart
    // in the first frames. Each new blob's particles are looked up among the earlier blobs'
    // (a hash of cells kOverlapReach of the smallest spacing wide): every point of a blob's
    // area lies within 0.71 spacings of one of its particles, a neighbouring blob's particles
    // a spacing or more away. The level gets a warning per blob overlapped.
    // A nozzle inside a solid or outside the container places nothing there (World::step
    // counts its particles as skipped): say so, as for a blob's left-out lattice points.
    void warnBuriedNozzle(const std::string& at, glm::vec2 nozzle) {
        const auto boundaries = m_level.world.boundaries();
        for (const Level::PluginEntry& plugin : m_level.plugins) {
            if (plugin.kind == PluginKind::Boundary && boundaries[plugin.index]->contains(nozzle)) {
                m_level.warnings.push_back(m_doc.locatedText(
                    at, "the emitter's nozzle [" + formatNumber(nozzle.x) + ", " +
                            formatNumber(nozzle.y) +
                            "] lies inside a solid or outside the "
                            "container of plugin \"" +
                            plugin.name + "\": it places no particle there (counted as skipped)"));
                return;
            }
        }
    }

    void warnOverlaps(const std::string& at, std::size_t blob, uint32_t first, float spacing) {
        const World& world = m_level.world;
        const std::span<const float> x = world.positionX(), y = world.positionY();
        const uint32_t end = world.particleCount();
        if (m_blobStarts.empty()) { // the materials are all known before the blobs
            m_overlapCell = kOverlapReach * double(spacing);
            for (uint16_t m = 0; m < world.materialCount(); ++m) {
                m_overlapCell =
                    std::min(m_overlapCell, kOverlapReach * double(world.spacing(MaterialId{m})));
            }
        }
        const double cell = m_overlapCell;
        auto key = [&](double cx, double cy) {
            return (int64_t(std::floor(cx / cell)) * 73856093) ^
                   (int64_t(std::floor(cy / cell)) * 19349663);
        };
        // Particles of earlier blobs within half a spacing, counted per earlier blob.
        std::vector<uint32_t> hits(m_blobStarts.size(), 0);
        const double reach2 = cell * cell;
        for (uint32_t i = first; i < end; ++i) {
            bool counted = false;
            for (int dy = -1; dy <= 1 && !counted; ++dy) {
                for (int dx = -1; dx <= 1 && !counted; ++dx) {
                    const auto found = m_cells.find(key(x[i] + dx * cell, y[i] + dy * cell));
                    if (found == m_cells.end()) {
                        continue;
                    }
                    for (const uint32_t j : found->second) {
                        const double ex = double(x[i]) - x[j], ey = double(y[i]) - y[j];
                        if (ex * ex + ey * ey < reach2) {
                            const auto owner =
                                std::upper_bound(m_blobStarts.begin(), m_blobStarts.end(), j) -
                                m_blobStarts.begin() - 1;
                            ++hits[std::size_t(owner)];
                            counted = true;
                            break;
                        }
                    }
                }
            }
        }
        for (std::size_t k = 0; k < hits.size(); ++k) {
            if (hits[k] == 0) {
                continue;
            }
            m_level.warnings.push_back(m_doc.locatedText(
                at, std::to_string(hits[k]) + " of the blob's " + std::to_string(end - first) +
                        " particles lie inside blob " + std::to_string(m_blobIndex[k]) +
                        " (closer than 0.8 lattice spacings to its particles): the liquid there "
                        "starts at about twice its rest density and bursts apart; move or "
                        "shrink one of them"));
        }
        m_blobStarts.push_back(first);
        m_blobIndex.push_back(blob);
        for (uint32_t i = first; i < end; ++i) {
            m_cells[key(x[i], y[i])].push_back(i);
        }
    }

    // The world fills a blob's bounding box on the material's lattice; refuse boxes that would
    // span more lattice cells than the world may hold before asking it to. Returns the
    // blob's lattice points (unit: count).
    double checkBlobSize(const ObjectReader& b, const Shape& shape, MaterialId material) const {
        glm::dvec2 lo{shape.center - shape.halfExtents}, hi{shape.center + shape.halfExtents};
        if (shape.type == ShapeType::Circle) {
            lo = glm::dvec2(shape.center) - double(shape.radius);
            hi = glm::dvec2(shape.center) + double(shape.radius);
        } else if (shape.type == ShapeType::Polygon) {
            lo = hi = shape.vertices[0];
            for (const glm::vec2 v : shape.vertices) {
                lo = glm::min(lo, glm::dvec2(v));
                hi = glm::max(hi, glm::dvec2(v));
            }
        }
        const double spacing = m_level.world.spacing(material);
        const double cols = std::floor((hi.x - lo.x) / spacing);
        const double rows = std::floor((hi.y - lo.y) / spacing);
        const double cap = m_level.world.def().maxParticles;
        if (!(cols <= cap && rows <= cap && cols * rows <= cap)) {
            b.fail("the blob spans about " +
                   formatNumber(std::max(cols, 1.0) * std::max(rows, 1.0)) +
                   " lattice points (spacing " + formatNumber(float(spacing)) +
                   " m); the world holds at most " + formatNumber(cap) +
                   " particles (world.maxParticles)");
        }
        return std::max(cols, 1.0) * std::max(rows, 1.0);
    }

    // ---- emitters, drains, sensors ---------------------------------------------------------
    void readEmitters(const ObjectReader& root) {
        const Json* list = root.array("emitters", "emitters");
        for (std::size_t i = 0; list != nullptr && i < list->size(); ++i) {
            const std::string at = childPointer(root.pointer("emitters"), i);
            const ObjectReader e(m_doc, (*list)[i], at, "an emitter");
            std::vector<std::string_view> allowed{"name", "material", "position", "direction"};
            addNames(allowed, emitterFields());
            allowed.push_back("seed");
            e.allowOnly(allowed);
            const std::string name = requiredName(e, "emitter");
            EmitterDef def;
            def.material =
                m_materials.find(m_doc, e.requiredString("material", "the name of a material"),
                                 e.pointer("material"));
            def.position = e.requiredPoint("position", kCoordinate);
            def.direction = e.point("direction", {-1e3, 1e3, "1"}, def.direction);
            if (def.direction.x == 0.0f && def.direction.y == 0.0f) {
                e.failAt("direction", "expected a direction other than [0, 0]");
            }
            readFields(e, emitterFields(), def);
            def.seed = e.integer("seed", {0, 9007199254740992.0, "1"}, def.seed);
            const EmitterId id = located(m_doc, at, [&] { return m_level.world.addEmitter(def); });
            warnBuriedNozzle(at, def.position);
            m_emitterNames.add(m_doc, name, e.pointer("name"), id);
            m_level.emitters.emplace_back(name, id);
        }
    }

    void readDrains(const ObjectReader& root) {
        const Json* list = root.array("drains", "drains");
        for (std::size_t i = 0; list != nullptr && i < list->size(); ++i) {
            const std::string at = childPointer(root.pointer("drains"), i);
            const ObjectReader d(m_doc, (*list)[i], at, "a drain");
            DrainDef def;
            def.shape = readShape(d, {"name", "material"});
            const std::string name = requiredName(d, "drain");
            if (d.has("material")) {
                def.onlyMaterial = true;
                def.material =
                    m_materials.find(m_doc, d.requiredString("material", "the name of a material"),
                                     d.pointer("material"));
            }
            const DrainId id = located(m_doc, at, [&] { return m_level.world.addDrain(def); });
            m_drainNames.add(m_doc, name, d.pointer("name"), id);
            m_level.drains.emplace_back(name, id);
        }
    }

    void readSensors(const ObjectReader& root) {
        const Json* list = root.array("sensors", "sensors");
        for (std::size_t i = 0; list != nullptr && i < list->size(); ++i) {
            const std::string at = childPointer(root.pointer("sensors"), i);
            const ObjectReader s(m_doc, (*list)[i], at, "a sensor");
            SensorDef def;
            def.shape = readShape(s, {"name"});
            const std::string name = requiredName(s, "sensor");
            const SensorId id = located(m_doc, at, [&] { return m_level.world.addSensor(def); });
            m_sensorNames.add(m_doc, name, s.pointer("name"), id);
            m_level.sensors.emplace_back(name, id);
        }
    }

    // ---- goal ----------------------------------------------------------------------------
    void readGoal(const ObjectReader& root) {
        const Json* value = root.find("goal");
        if (value == nullptr) {
            return;
        }
        const ObjectReader g(m_doc, *value, root.pointer("goal"), "a goal");
        std::vector<std::string_view> allowed{"sensor", "material"};
        for (const EnumName<GoalMeasure>& row : kGoalMeasureNames) {
            allowed.push_back(row.name);
        }
        allowed.insert(allowed.end(), {"timeLimit", "description"});
        g.allowOnly(allowed);
        LevelGoal& goal = m_level.goal;
        goal.sensorName = g.requiredString("sensor", "the name of a sensor");
        goal.sensor = m_sensorNames.find(m_doc, goal.sensorName, g.pointer("sensor"));
        goal.materialName = g.requiredString("material", "the name of a material");
        goal.material = m_materials.find(m_doc, goal.materialName, g.pointer("material"));

        // Exactly one amount; a second one is reported at its key.
        std::string known;
        std::vector<std::string_view> given;
        for (const EnumName<GoalMeasure>& row : kGoalMeasureNames) {
            known += (known.empty() ? "'" : ", '") + std::string(row.name) + "'";
            if (g.has(row.name)) {
                given.push_back(row.name);
            }
        }
        if (given.empty()) {
            g.fail("missing the amount; expected one of " + known);
        }
        if (given.size() > 1) {
            std::sort(given.begin(), given.end(), [&](std::string_view a, std::string_view b) {
                return m_doc.keyOffset(g.pointer(a)) < m_doc.keyOffset(g.pointer(b));
            });
            m_doc.failAtKey(g.pointer(given[1]), "expected only one of " + known + "; '" +
                                                     std::string(given[0]) + "' is given too");
        }
        goal.measure = *valueIn(kGoalMeasureNames, given[0]);
        switch (goal.measure) {
        case GoalMeasure::Fraction:
            goal.amount = g.number(given[0], {0, 1, "1", true}, 0.0);
            break;
        case GoalMeasure::Count:
            goal.amount = double(g.integer(given[0], {1, double(1u << 26), "count"}, 0));
            break;
        case GoalMeasure::Volume:
            goal.amount = g.number(given[0], {0, 1e6, "m^3", true}, 0.0);
            break;
        }
        goal.timeLimit = g.number("timeLimit", kLifetime, 0.0);
        goal.description = g.string("description", "");
        goal.present = true;
    }

    const JsonDocument& m_doc;
    const Registry& m_registry;
    const LevelOptions& m_options;
    Level& m_level;
    float colourMixing = 0.0f; // the world's "colourMixing" (1/s)
    // Overlapping blobs (warnOverlaps): the first particle of each blob read so far and the
    // blob's index in the file, the particles by cell, the cell size (m).
    std::vector<uint32_t> m_blobStarts;
    std::vector<std::size_t> m_blobIndex;
    std::unordered_map<int64_t, std::vector<uint32_t>> m_cells;
    double m_overlapCell = 0.0;
    NameTable<MaterialId> m_materials{"material"};
    NameTable<uint32_t> m_pluginNames{"plugin"};
    NameTable<EmitterId> m_emitterNames{"emitter"};
    NameTable<DrainId> m_drainNames{"drain"};
    NameTable<SensorId> m_sensorNames{"sensor"};
};

} // namespace

// ---- Level -------------------------------------------------------------------------------

double Level::goalValue() const {
    if (!goal.present) {
        return 0.0;
    }
    const std::span<const SensorReading> readings = world.sensorReading(goal.sensor);
    if (goal.material.index >= readings.size()) {
        return 0.0;
    }
    const SensorReading& r = readings[goal.material.index];
    switch (goal.measure) {
    case GoalMeasure::Count:
        return double(r.count);
    case GoalMeasure::Volume:
        return double(r.volume);
    case GoalMeasure::Fraction:
        return double(r.area) / double(area(world.sensor(goal.sensor).shape));
    }
    return 0.0;
}

GoalState Level::goalState() const {
    if (!goal.present) {
        return GoalState::None;
    }
    if (m_goalState == GoalState::Pending) {
        if (goalValue() >= goal.amount) {
            m_goalState = GoalState::Won;
        } else if (goal.timeLimit > 0.0 && world.time() >= goal.timeLimit) {
            m_goalState = GoalState::Lost;
        }
    }
    return m_goalState;
}

Level& Level::operator=(Level&& other) noexcept {
    if (this == &other) {
        return *this;
    }
    // The coupling refers to this level's world (its plugin) and Box2D world: it goes before
    // either is replaced. The rest is member by member, in declaration order.
    coupling.reset();
    joints.clear();
    bodies.clear();
    physics.reset();
    file = std::move(other.file);
    source = std::move(other.source);
    name = std::move(other.name);
    description = std::move(other.description);
    version = other.version;
    frameRate = other.frameRate;
    world = std::move(other.world);
    materials = std::move(other.materials);
    emitters = std::move(other.emitters);
    drains = std::move(other.drains);
    sensors = std::move(other.sensors);
    plugins = std::move(other.plugins);
    goal = std::move(other.goal);
    physics = std::move(other.physics);
    coupling = std::move(other.coupling);
    bodies = std::move(other.bodies);
    joints = std::move(other.joints);
    warnings = std::move(other.warnings);
    m_goalState = other.m_goalState;
    return *this;
}

void Level::step() {
    step(1.0f / frameRate);
}

void Level::step(float frameDt) {
    const float dt = frameDt;
    if (coupling) {
        coupling->step(world, dt);
    } else {
        world.step(dt);
    }
    goalState();
}

void Level::destroyBody(b2Body* body) {
    if (world.stepping()) {
        throw Error("Level::destroyBody: called during the world's own step (from a plugin's "
                    "hook); a body is destroyed only between frames",
                    ErrorCode::WrongState);
    }
    bool found = false;
    if (physics != nullptr && body != nullptr) {
        for (const b2Body* b = physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
            found = found || b == body;
        }
    }
    if (!found) {
        throw Error("Level::destroyBody: the body is not in this level's Box2D world",
                    ErrorCode::StaleId);
    }
    // Box2D destroys the joints attached to the body with it: drop their names first.
    std::erase_if(joints, [&](const std::pair<std::string, b2Joint*>& j) {
        return j.second->GetBodyA() == body || j.second->GetBodyB() == body;
    });
    std::erase_if(bodies, [&](const std::pair<std::string, b2Body*>& b) { return b.second == body; });
    // Its contact events go with it: a body made before the next step at its address must not
    // inherit the setting.
    if (coupling) {
        coupling->setContactEvents(body, false);
    }
    physics->DestroyBody(body);
}

Level parseLevel(std::string_view text, std::string_view file, const Registry& registry,
                 const LevelOptions& options) {
    const detail::JsonDocument doc(text, file);
    Level level;
    level.file = std::string(file);
    level.source = std::string(text);
    LevelReader(doc, registry, options, level).read();
    return level;
}

Level loadLevel(const std::string& path, const Registry& registry, const LevelOptions& options) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
        throw Error("loadLevel: cannot open '" + path +
                        "': " + std::generic_category().message(errno),
                    ErrorCode::Io);
    }
    std::string text;
    char buffer[65536];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0) {
        text.append(buffer, n);
    }
    const bool failed = std::ferror(f) != 0;
    const int error = errno;
    std::fclose(f);
    if (failed) {
        throw Error("loadLevel: cannot read '" + path +
                        "': " + std::generic_category().message(error),
                    ErrorCode::Io);
    }
    return parseLevel(text, path, registry, options);
}

} // namespace fluid
