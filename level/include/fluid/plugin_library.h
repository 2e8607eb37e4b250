// fluid::level — plugin libraries: force and boundary plugins compiled into a shared library
// and loaded at run time (`fluid-run --plugin`, the demo). Writing one: docs/plugins.md.
#pragma once

#include <fluid/error.h>
#include <fluid/plugin_abi.h>
#include <fluid/registry.h>

#include <string>
#include <vector>

namespace fluid {

/// What `loadPluginLibrary` loaded. Plain data: the library itself stays loaded regardless of
/// this object's lifetime (see `loadPluginLibrary`).
struct PluginLibrary {
    /// The path as given to `loadPluginLibrary`.
    std::string path;
    /// The plugin types the library registered, in registration order (e.g. "force.whirlpool").
    std::vector<std::string> types;
};

/// Loads the plugin library at `path` (a shared library defining the entry points of
/// `FLUID_PLUGIN_ENTRY`, see <fluid/plugin_abi.h>) and adds its plugin types to `registry`.
///
/// Checks, in order, before any plugin code runs: the file opens as a shared library, it has
/// the `fluid_plugin_abi_version` and `fluid_register_plugins` entry points, its ABI version is
/// `kPluginAbiVersion`, and its `pluginAbiDetails()` (declaration hash, compiler, standard
/// library, struct sizes) equal this build's. Then the library registers into an empty scratch
/// registry, and its types are added to `registry` all together: on any error `registry` is
/// left unchanged. Throws `fluid::Error` naming the path:
/// - "cannot load plugin library 'PATH': DLERROR" (missing file, not a shared library,
///   unresolved symbols);
/// - "'PATH' is not a fluid plugin library: it has no fluid_plugin_abi_version /
///   fluid_register_plugins entry point";
/// - "'PATH' was built for plugin ABI N; this fluid has ABI M: rebuild the plugin against this
///   fluid" (and a similar message naming the first differing detail);
/// - "plugin library 'PATH': MESSAGE" when registration throws or a type is already in
///   `registry` (e.g. the same library loaded twice).
///
/// A `path` without a '/' is taken relative to the current directory (plain dlopen() would
/// search the system library path instead).
///
/// Lifetime rule: a loaded library is never unloaded. Its code backs the registry's factories,
/// the plugins they make (vtables, `apply`) and their parameter declarations, so unloading it
/// while any registry copy or plugin from it is alive would crash; fluid therefore keeps it
/// loaded until the process exits. (A library refused before its registration ran is closed
/// again.) Loading the same file twice maps it once; the second load then fails on the
/// duplicate types unless it targets another registry.
///
/// Thread rule: modifies `registry`, which is not synchronised: call it on the thread that owns
/// the registry, before sharing the registry or stepping a world with plugins from it.
PluginLibrary loadPluginLibrary(const std::string& path, Registry& registry);

} // namespace fluid
