// fluid — plugin parameters and the registry.
#include <fluid/error.h>
#include <fluid/internal/checks.h>
#include <fluid/plugin.h>
#include <fluid/registry.h>

#include <cmath>
#include <sstream>

namespace fluid {

Plugin::Plugin(std::string_view type, PluginKind kind, std::span<const ParamDecl> params)
    : m_type(type), m_kind(kind), m_decls(params) {
    m_values.reserve(params.size());
    for (const ParamDecl& decl : params) {
        m_values.push_back(decl.type == ParamType::Number ? decl.defaultValue : 0.0);
    }
    m_points.resize(params.size());
}

namespace {
std::size_t findParam(std::string_view type, std::span<const ParamDecl> decls,
                      std::string_view name) {
    for (std::size_t i = 0; i < decls.size(); ++i) {
        if (decls[i].name == name) {
            return i;
        }
    }
    std::ostringstream s;
    s << "plugin " << internal::quoted(type) << ": unknown parameter " << internal::quoted(name)
      << "; known:";
    for (const ParamDecl& decl : decls) {
        s << ' ' << decl.name;
    }
    if (decls.empty()) {
        s << " (none)";
    }
    throw Error(s.str(), ErrorCode::UnknownName);
}

void checkType(std::string_view type, const ParamDecl& decl, ParamType expected) {
    if (decl.type != expected) {
        throw Error("plugin " + internal::quoted(type) + ": parameter " +
                        internal::quoted(decl.name) + " is " +
                        (decl.type == ParamType::Points ? "a point list" : "a number") + ", not " +
                        (expected == ParamType::Points ? "a point list" : "a number"),
                    ErrorCode::BadArgument);
    }
}

void checkValue(std::string_view type, const ParamDecl& decl, double value) {
    if (decl.type == ParamType::Points) {
        return; // points: checked by setPoints
    }
    if (std::isfinite(value) && value >= decl.minValue && value <= decl.maxValue) {
        return;
    }
    std::ostringstream s;
    s << "plugin " << internal::quoted(type) << ": parameter " << internal::quoted(decl.name)
      << " = " << value << " is "
      << (std::isfinite(value) ? "out of range" : "not finite; expected") << " [" << decl.minValue
      << ", " << decl.maxValue << "] (unit: " << decl.unit << ")";
    throw Error(s.str(), std::isfinite(value) ? ErrorCode::OutOfRange : ErrorCode::BadArgument);
}
} // namespace

double Plugin::param(std::string_view name) const {
    const std::size_t index = findParam(m_type, m_decls, name);
    checkType(m_type, m_decls[index], ParamType::Number);
    return m_values[index];
}

void Plugin::setParam(std::string_view name, double value) {
    const std::size_t index = findParam(m_type, m_decls, name);
    checkType(m_type, m_decls[index], ParamType::Number);
    checkValue(m_type, m_decls[index], value);
    // A plugin may refuse a value its declaration allows (geometry that does not fit): then
    // the old value stays.
    const double old = m_values[index];
    m_values[index] = value;
    try {
        onParamChanged(index);
    } catch (...) {
        m_values[index] = old;
        throw;
    }
}

std::span<const glm::vec2> Plugin::points(std::string_view name) const {
    const std::size_t index = findParam(m_type, m_decls, name);
    checkType(m_type, m_decls[index], ParamType::Points);
    return m_points[index];
}

void Plugin::setPoints(std::string_view name, std::span<const glm::vec2> points) {
    const std::size_t index = findParam(m_type, m_decls, name);
    const ParamDecl& decl = m_decls[index];
    checkType(m_type, decl, ParamType::Points);
    const auto count = double(points.size());
    if (!(count >= decl.minValue && count <= decl.maxValue)) {
        std::ostringstream s;
        s << "plugin " << internal::quoted(m_type) << ": parameter " << internal::quoted(decl.name)
          << " has " << points.size() << " points; expected " << decl.minValue << " to "
          << decl.maxValue;
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
        if (!std::isfinite(points[k].x) || !std::isfinite(points[k].y)) {
            std::ostringstream s;
            s << "plugin " << internal::quoted(m_type) << ": parameter "
              << internal::quoted(decl.name) << " point " << k << " = (" << points[k].x << ", "
              << points[k].y << ") is not finite";
            throw Error(s.str(), ErrorCode::BadArgument);
        }
    }
    std::vector<glm::vec2> old(points.begin(), points.end());
    m_points[index].swap(old);
    try {
        onParamChanged(index);
    } catch (...) {
        m_points[index].swap(old);
        throw;
    }
}

void Registry::add(PluginInfo info) {
    if (info.type.empty()) {
        throw Error("Registry::add: empty plugin type", ErrorCode::BadArgument);
    }
    internal::checkName("Registry::add: plugin type", info.type);
    const std::string type = "Registry::add: plugin type " + internal::quoted(info.type);
    if (find(info.type) != nullptr) {
        throw Error(type + " is already registered", ErrorCode::BadArgument);
    }
    if (!info.create) {
        throw Error(type + " has no factory", ErrorCode::BadArgument);
    }
    for (size_t i = 0; i < info.params.size(); ++i) {
        const ParamDecl& decl = info.params[i];
        internal::checkName(type + " parameter", decl.name);
        for (size_t j = 0; j < i; ++j) {
            if (info.params[j].name == decl.name) {
                throw Error(type + " declares parameter " + internal::quoted(decl.name) + " twice",
                            ErrorCode::BadArgument);
            }
        }
        if (decl.type == ParamType::Points &&
            !(decl.minValue >= 0.0 && decl.minValue <= decl.maxValue)) {
            throw Error(type + " point list " + internal::quoted(decl.name) +
                            " has no valid count range [minValue, maxValue]",
                        ErrorCode::BadArgument);
        }
        checkValue(info.type, decl, decl.defaultValue);
    }
    m_infos.push_back(std::move(info));
}

const PluginInfo* Registry::find(std::string_view type) const {
    for (const PluginInfo& info : m_infos) {
        if (info.type == type) {
            return &info;
        }
    }
    return nullptr;
}

std::unique_ptr<Plugin> Registry::create(std::string_view type,
                                         std::span<const ParamValue> values) const {
    const PluginInfo* info = find(type);
    if (info == nullptr) {
        std::ostringstream s;
        s << "unknown plugin type " << internal::quoted(type) << "; known:";
        for (const PluginInfo& known : m_infos) {
            s << ' ' << known.type;
        }
        if (m_infos.empty()) {
            s << " (none: call registerBuiltinPlugins first)";
        }
        throw Error(s.str(), ErrorCode::UnknownName);
    }
    std::unique_ptr<Plugin> plugin = info->create();
    for (const ParamValue& value : values) {
        plugin->setParam(value.first, value.second);
    }
    plugin->checkParams();
    return plugin;
}

namespace {
template <class P>
std::unique_ptr<P> downcast(std::unique_ptr<Plugin> plugin, PluginKind kind, const char* what) {
    if (plugin->kind() != kind) {
        throw Error("plugin " + internal::quoted(plugin->type()) + " is not a " + what + " plugin",
                    ErrorCode::BadArgument);
    }
    return std::unique_ptr<P>(static_cast<P*>(plugin.release()));
}
} // namespace

std::unique_ptr<ForcePlugin> Registry::createForce(std::string_view type,
                                                   std::span<const ParamValue> values) const {
    return downcast<ForcePlugin>(create(type, values), PluginKind::Force, "force");
}

std::unique_ptr<BoundaryPlugin> Registry::createBoundary(std::string_view type,
                                                         std::span<const ParamValue> values) const {
    return downcast<BoundaryPlugin>(create(type, values), PluginKind::Boundary, "boundary");
}

} // namespace fluid
