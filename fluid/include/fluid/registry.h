// fluid — 2D SPH liquid for games.
#pragma once

#include <fluid/plugin.h>

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace fluid {

/// How the registry describes and makes one plugin type.
struct PluginInfo {
    /// Type string used in level files: "force.<name>" or "boundary.<name>" (a name: printable
    /// text of 1 to `kMaxNameBytes` bytes).
    std::string type;
    /// Force or boundary.
    PluginKind kind = PluginKind::Force;
    /// One line for humans.
    std::string description;
    /// Declared parameters (must outlive the registry; usually the class's static array).
    std::span<const ParamDecl> params;
    /// Makes a plugin with default parameter values.
    std::function<std::unique_ptr<Plugin>()> create;
};

/// A parameter value given by name when creating a plugin.
using ParamValue = std::pair<std::string, double>;

/// Creates plugins by string type with self-describing parameters. No globals: make one, call
/// `registerBuiltinPlugins(registry)` (fluid/plugins/builtin.h), add your own.
/// Thread rule: not synchronised; fill it before sharing it read-only between threads.
class Registry {
public:
    /// Adds a type; throws `fluid::Error` if the type is empty, not a name (a control
    /// character, more than `kMaxNameBytes` bytes: "Registry::add: plugin type 'a\x07': the
    /// name holds a control character (byte 0x07 at offset 1); names are printable text"),
    /// already registered, has no factory, declares a parameter whose name is not one or a
    /// name twice, or a declared default lies outside its range.
    void add(PluginInfo info);
    /// Convenience: registers `P` using `P::kType`, `P::kParams` and its default constructor.
    template <class P> void add(std::string description) {
        add(PluginInfo{std::string(P::kType),
                       std::is_base_of_v<ForcePlugin, P> ? PluginKind::Force : PluginKind::Boundary,
                       std::move(description), std::span<const ParamDecl>(P::kParams),
                       [] { return std::unique_ptr<Plugin>(new P()); }});
    }
    /// The type's description, or nullptr if unknown.
    const PluginInfo* find(std::string_view type) const;
    /// Every registered type, in registration order.
    std::span<const PluginInfo> types() const { return m_infos; }

    /// Makes a plugin and sets `values` (validated as in `Plugin::setParam`, then together by
    /// `Plugin::checkParams`). Throws `fluid::Error` for an unknown type (listing the known
    /// ones), a bad value or values that do not fit together.
    std::unique_ptr<Plugin> create(std::string_view type,
                                   std::span<const ParamValue> values = {}) const;
    /// As `create`, and throws `fluid::Error` unless the type is a force plugin.
    std::unique_ptr<ForcePlugin> createForce(std::string_view type,
                                             std::span<const ParamValue> values = {}) const;
    /// As `create`, and throws `fluid::Error` unless the type is a boundary plugin.
    std::unique_ptr<BoundaryPlugin> createBoundary(std::string_view type,
                                                   std::span<const ParamValue> values = {}) const;

private:
    std::vector<PluginInfo> m_infos;
};

} // namespace fluid
