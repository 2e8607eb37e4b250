// fluid::c — plugins written in C (fluid/c.h): a ForcePlugin and a BoundaryPlugin that call a
// table of function pointers with a user pointer, under the C++ plugins' contracts.
#include "c_internal.h"

#include <fluid/internal/checks.h>

#include <cmath>
#include <cstddef>
#include <deque>
#include <mutex>

namespace fluid::c {

namespace {

// A C plugin's type as its messages quote it: "plugin type 'force.x'", bounded; "(no type)".
std::string typeOf(const char* type) {
    return type != nullptr ? "plugin type " + internal::quoted(type) : "(no type)";
}

// The plugin's type and parameter declarations, copied from the C def. A base class of the
// adapters, so that it is built before fluid::Plugin, which keeps a span of the declarations.
struct Declarations {
    std::string type;
    std::vector<std::string> text; // names, units and descriptions; reserved, never moved
    std::vector<ParamDecl> decls;
    std::vector<double> values;     // the parameters' values, as the callbacks read them

    Declarations(const char* typeName, const fluid_param_decl* params, uint32_t count,
                 const char* function) {
        need(typeName, function, "def->type");
        if (*typeName == '\0') {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT, std::string(function) +
                                                            ": def->type is empty"};
        }
        // The names' rule (printable, at most kMaxNameBytes): the type's, then each parameter's.
        internal::checkName(std::string(function) + ": plugin type", typeName);
        type = typeName;
        if (count > 0) {
            need(params, function, "def->params");
        }
        text.reserve(3 * size_t(count));
        decls.reserve(count);
        for (uint32_t i = 0; i < count; ++i) {
            const fluid_param_decl& p = params[i];
            need(p.name, function, "a parameter's name");
            const std::string owner =
                std::string(function) + ": plugin type " + internal::quoted(type) + " parameter";
            internal::checkName(owner, p.name);
            const std::string where = owner + " " + internal::quoted(p.name);
            if (!std::isfinite(p.default_value) || !std::isfinite(p.min_value) ||
                !std::isfinite(p.max_value) || p.min_value > p.max_value ||
                p.default_value < p.min_value || p.default_value > p.max_value) {
                throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                              where + ": the default must lie in [min_value, max_value], all "
                                      "finite"};
            }
            text.emplace_back(p.name);
            const std::string_view name = text.back();
            text.emplace_back(p.unit != nullptr ? p.unit : "");
            const std::string_view unit = text.back();
            text.emplace_back(p.description != nullptr ? p.description : "");
            const std::string_view description = text.back();
            decls.push_back(ParamDecl{name, unit, p.default_value, p.min_value, p.max_value,
                                      description, ParamType::Number});
        }
    }
};

fluid_step_context toC(const StepContext& c, const double* params) {
    return {c.frameDt, c.time, c.sampleSpacing, c.supportRadius, params};
}

// What a force and a boundary written in C share: the declarations (built before `Base`), the
// parameter values the callbacks read, the user pointer and its destroy callback.
template <class Base> class CPlugin : protected Declarations, public Base {
public:
    ~CPlugin() override {
        if (m_destroy != nullptr) {
            m_destroy(m_user);
        }
    }
    CPlugin(const CPlugin&) = delete;
    CPlugin& operator=(const CPlugin&) = delete;

    // The destroy callback runs when the world lets the plugin go, not when adding it failed:
    // held back until the world has it.
    void holdDestroy() {
        m_held = m_destroy;
        m_destroy = nullptr;
    }
    void releaseDestroy() { m_destroy = m_held; }

protected:
    CPlugin(const char* typeName, const fluid_param_decl* params, uint32_t count,
            const char* function, void* user, void (*destroy)(void*))
        : Declarations(typeName, params, count, function), Base(Declarations::type, decls),
          m_user(user), m_destroy(destroy) {
        refresh();
    }
    // The values in `values`, for the callbacks (which may run on worker threads: read only).
    void refresh() {
        values.resize(decls.size());
        for (size_t i = 0; i < decls.size(); ++i) {
            values[i] = this->value(i);
        }
    }
    void onParamChanged(std::size_t) override { refresh(); }

    void* m_user = nullptr;

private:
    void (*m_destroy)(void*) = nullptr;
    void (*m_held)(void*) = nullptr;
};

class CForce final : public CPlugin<ForcePlugin> {
public:
    explicit CForce(const fluid_force_plugin_def& def)
        : CPlugin(checked(def).type, def.params, def.param_count, "fluid_world_add_force",
                  def.user, def.destroy),
          m_def(def) {}

    void prepare(const StepContext& context) override {
        refresh();
        if (m_def.prepare != nullptr) {
            const fluid_step_context c = toC(context, values.data());
            m_def.prepare(m_user, &c);
        }
    }

    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override {
        const ParticleView& p = context.particles;
        const fluid_force_context c{p.px.data(),       p.py.data(),       p.vx.data(),
                                    p.vy.data(),       p.material.data(), p.count,
                                    context.ax.data(), context.ay.data(), context.dt,
                                    context.time,      values.data()};
        m_def.apply(m_user, &c, begin, end);
    }

private:
    // `def` once its callbacks are checked: before anything is built, so that a refused def
    // never has its destroy called.
    static const fluid_force_plugin_def& checked(const fluid_force_plugin_def& def) {
        if (def.apply == nullptr) {
            throw Failure{FLUID_ERROR_NULL_ARGUMENT,
                          "fluid_world_add_force: " + typeOf(def.type) + ": def->apply is NULL"};
        }
        return def;
    }

    fluid_force_plugin_def m_def;
};

static_assert(sizeof(fluid_rigid_body) == sizeof(RigidBody) &&
                  offsetof(fluid_rigid_body, contacts) == offsetof(RigidBody, contacts),
              "fluid_rigid_body's layout");
static_assert(sizeof(fluid_rigid_body_impulse) == sizeof(RigidBodyImpulse),
              "fluid_rigid_body_impulse's layout");
static_assert(sizeof(fluid_body_shift) == sizeof(BodyShift) &&
                  offsetof(fluid_body_shift, offset) == offsetof(BodyShift, offset),
              "fluid_body_shift's layout");

class CBoundary final : public CPlugin<BoundaryPlugin> {
public:
    explicit CBoundary(const fluid_boundary_plugin_def& def)
        : CPlugin(checked(def).type, def.params, def.param_count, "fluid_world_add_boundary",
                  def.user, def.destroy),
          m_def(def) {}

    void prepare(const StepContext& context) override {
        refresh();
        const fluid_step_context c = toC(context, values.data());
        fluid_boundary_samples samples{};
        m_def.prepare(m_user, &c, &samples);
        m_samples.clear();
        if (samples.count > 0 && (samples.px == nullptr || samples.py == nullptr)) {
            throw Error(Declarations::type + ": prepare left " + std::to_string(samples.count) +
                            " samples without their positions (px or py is NULL)",
                        ErrorCode::WrongState);
        }
        for (uint32_t i = 0; i < samples.count; ++i) {
            m_samples.add(samples.px[i], samples.py[i],
                          samples.vx != nullptr ? samples.vx[i] : 0.0f,
                          samples.vy != nullptr ? samples.vy[i] : 0.0f);
        }
        m_bodies.clear();
        if (m_def.rigid_bodies != nullptr) {
            const fluid_rigid_body* bodies = nullptr;
            const uint32_t count = m_def.rigid_bodies(m_user, &bodies);
            if (count > 0 && bodies == nullptr) {
                throw Error(Declarations::type + ": rigid_bodies returned " +
                                std::to_string(count) + " bodies and a NULL array",
                            ErrorCode::WrongState);
            }
            for (uint32_t i = 0; i < count; ++i) {
                m_bodies.push_back(
                    RigidBody{bodies[i].mass, bodies[i].sample_begin, bodies[i].sample_end});
            }
        }
    }

    void project(const ProjectContext& context, uint32_t begin, uint32_t end) override {
        const fluid_project_context c{
            context.px.data(),
            context.py.data(),
            context.prevX.data(),
            context.prevY.data(),
            context.vx.data(),
            context.vy.data(),
            context.material.data(),
            context.dt,
            context.timeInStep,
            context.prevTimeInStep,
            context.spacing,
            values.data(),
            context.bodyShifts.empty()
                ? nullptr
                : reinterpret_cast<const fluid_body_shift*>(context.bodyShifts.data()),
            uint32_t(context.bodyShifts.size())};
        m_def.project(m_user, &c, begin, end);
    }

    bool wantsForces() const override { return m_def.wants_forces; }

    BoundaryRole role() const override {
        return m_def.role == FLUID_ROLE_WALL        ? BoundaryRole::Wall
               : m_def.role == FLUID_ROLE_CONTAINER ? BoundaryRole::Container
                                                    : BoundaryRole::Solid;
    }

    void receiveForces(std::span<const float> fx, std::span<const float> fy,
                       std::span<const float> drag) override {
        if (m_def.receive_forces != nullptr) {
            m_def.receive_forces(m_user, fx.data(), fy.data(), drag.data(),
                                 uint32_t(fx.size()));
        }
    }

    float friction() const override { return m_def.friction; }

    std::span<const RigidBody> rigidBodies() const override { return m_bodies; }

    void receiveBodyImpulses(std::span<const RigidBodyImpulse> impulses) override {
        if (m_def.receive_body_impulses == nullptr) {
            return;
        }
        m_impulses.resize(impulses.size());
        for (size_t i = 0; i < impulses.size(); ++i) {
            m_impulses[i] = {{impulses[i].impulse.x, impulses[i].impulse.y},
                             {impulses[i].displacement.x, impulses[i].displacement.y}};
        }
        m_def.receive_body_impulses(m_user, m_impulses.data(), uint32_t(m_impulses.size()));
    }

    bool bodyContains(uint32_t body, glm::vec2 point, float timeInStep) const override {
        return m_def.body_contains != nullptr &&
               m_def.body_contains(m_user, body, {point.x, point.y}, timeInStep);
    }

    bool contains(glm::vec2 point) const override {
        return m_def.contains != nullptr && m_def.contains(m_user, {point.x, point.y});
    }

private:
    // `def` once its callbacks, role and friction are checked: before anything is built.
    static const fluid_boundary_plugin_def& checked(const fluid_boundary_plugin_def& def) {
        const std::string who = "fluid_world_add_boundary: " + typeOf(def.type);
        if (def.prepare == nullptr || def.project == nullptr) {
            throw Failure{FLUID_ERROR_NULL_ARGUMENT,
                          who + ": def->prepare and def->project are required (NULL here)"};
        }
        if (def.role != FLUID_ROLE_SOLID && def.role != FLUID_ROLE_WALL &&
            def.role != FLUID_ROLE_CONTAINER) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          who + ": def->role " + std::to_string(def.role) +
                              " is not FLUID_ROLE_SOLID, FLUID_ROLE_WALL or FLUID_ROLE_CONTAINER"};
        }
        if (!(def.friction >= 0.0f) || !std::isfinite(def.friction)) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          who + ": def->friction must be finite and >= 0"};
        }
        return def;
    }

    fluid_boundary_plugin_def m_def;
    std::vector<RigidBody> m_bodies;
    std::vector<fluid_rigid_body_impulse> m_impulses;
};

// A registered C type: its declarations (for the registry's PluginInfo) and the same in C (for
// each instance's def), kept for the life of the process.
struct CType {
    explicit CType(const fluid_plugin_type_def& def)
        : declarations(def.type, def.params, def.param_count, "fluid_register_plugin_type"),
          factory(def) {
        for (const ParamDecl& d : declarations.decls) {
            // The strings are the declarations' own (views of std::strings: NUL-terminated).
            params.push_back({d.name.data(), d.unit.data(), d.defaultValue, d.minValue,
                              d.maxValue, d.description.data()});
        }
        // The record's own strings and declarations; the caller's are not kept.
        factory.type = declarations.type.c_str();
        factory.description = nullptr;
        factory.params = params.data();
    }
    Declarations declarations;
    std::vector<fluid_param_decl> params;
    fluid_plugin_type_def factory;
};

std::mutex g_typesMutex;

// The registry every C call reads (under g_typesMutex): the built-ins, then the C types.
Registry& typesLocked() {
    static Registry types = [] {
        Registry r;
        registerBuiltinPlugins(r);
        return r;
    }();
    return types;
}

// The C types' records; a deque, so that registering one never moves another.
std::deque<CType>& cTypesLocked() {
    static std::deque<CType> types;
    return types;
}

// A new instance of C type `t` (the registry's factory): the type's factory fills the callbacks,
// the type and parameters stay the type's. Throws fluid::Error naming the type when the factory
// refuses or leaves a required callback NULL.
std::unique_ptr<Plugin> makeInstance(const CType& t) {
    const std::string& name = t.declarations.type;
    auto refuse = [&](const std::string& why) {
        return Error("plugin type " + internal::quoted(name) + " (written in C): " + why,
                     ErrorCode::BadArgument);
    };
    try {
        if (t.factory.kind == FLUID_PLUGIN_FORCE) {
            fluid_force_plugin_def d = fluid_default_force_plugin_def();
            if (!t.factory.create_force(t.factory.user, &d)) {
                throw refuse("create_force refused");
            }
            d.type = name.c_str();
            d.params = t.params.data();
            d.param_count = uint32_t(t.params.size());
            return std::make_unique<CForce>(d);
        }
        fluid_boundary_plugin_def d = fluid_default_boundary_plugin_def();
        if (!t.factory.create_boundary(t.factory.user, &d)) {
            throw refuse("create_boundary refused");
        }
        d.type = name.c_str();
        d.params = t.params.data();
        d.param_count = uint32_t(t.params.size());
        return std::make_unique<CBoundary>(d);
    } catch (const Failure& f) {
        throw refuse(f.message);
    }
}

} // namespace

Registry registry() {
    std::lock_guard<std::mutex> lock(g_typesMutex);
    return typesLocked();
}

} // namespace fluid::c

using namespace fluid;
using namespace fluid::c;

extern "C" {

fluid_force_plugin_def fluid_default_force_plugin_def(void) { return fluid_force_plugin_def{}; }

fluid_boundary_plugin_def fluid_default_boundary_plugin_def(void) {
    fluid_boundary_plugin_def def{};
    def.role = FLUID_ROLE_SOLID;
    return def;
}

fluid_plugin_type_def fluid_default_plugin_type_def(void) {
    fluid_plugin_type_def def{};
    def.kind = FLUID_PLUGIN_FORCE;
    return def;
}

fluid_status fluid_register_plugin_type(const fluid_plugin_type_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_register_plugin_type";
        need(def, function, "def");
        need(def->type, function, "def->type");
        const std::string name = typeOf(def->type);
        if (def->kind != FLUID_PLUGIN_FORCE && def->kind != FLUID_PLUGIN_BOUNDARY) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          std::string(function) + ": " + name + ": kind " +
                              std::to_string(def->kind) +
                              " is not FLUID_PLUGIN_FORCE (0) or FLUID_PLUGIN_BOUNDARY (1)"};
        }
        if (def->kind == FLUID_PLUGIN_FORCE ? def->create_force == nullptr
                                            : def->create_boundary == nullptr) {
            throw Failure{FLUID_ERROR_NULL_ARGUMENT,
                          std::string(function) + ": " + name + ": def->" +
                              (def->kind == FLUID_PLUGIN_FORCE ? "create_force"
                                                               : "create_boundary") +
                              " is NULL"};
        }
        std::lock_guard<std::mutex> lock(g_typesMutex);
        std::deque<CType>& records = cTypesLocked();
        records.emplace_back(*def);
        const CType& record = records.back();
        PluginInfo info;
        info.type = record.declarations.type;
        info.kind = def->kind == FLUID_PLUGIN_FORCE ? PluginKind::Force : PluginKind::Boundary;
        info.description = def->description != nullptr ? def->description : "";
        info.params = record.declarations.decls;
        info.create = [&record] { return makeInstance(record); };
        try {
            typesLocked().add(std::move(info));
        } catch (...) {
            records.pop_back(); // never referred to: the registry refused it
            throw;
        }
    });
}

fluid_status fluid_world_add_force(fluid_world* world, const fluid_force_plugin_def* def,
                                   fluid_plugin_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_force");
        need(def, "fluid_world_add_force", "def");
        need(id, "fluid_world_add_force", "id");
        auto plugin = std::make_unique<CForce>(*def);
        CForce* added = plugin.get();
        added->holdDestroy();
        w.addForce(std::move(plugin));
        added->releaseDestroy();
        *id = {uint32_t(w.forces().size() - 1), FLUID_PLUGIN_FORCE, tagOf(w)};
    });
}

fluid_status fluid_world_add_boundary(fluid_world* world, const fluid_boundary_plugin_def* def,
                                      fluid_plugin_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_boundary");
        need(def, "fluid_world_add_boundary", "def");
        need(id, "fluid_world_add_boundary", "id");
        auto plugin = std::make_unique<CBoundary>(*def);
        CBoundary* added = plugin.get();
        added->holdDestroy();
        w.addBoundary(std::move(plugin));
        added->releaseDestroy();
        *id = {uint32_t(w.boundaries().size() - 1), FLUID_PLUGIN_BOUNDARY, tagOf(w)};
    });
}

} // extern "C"
