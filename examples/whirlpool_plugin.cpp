// whirlpool_plugin: the C entry points that turn the whirlpool of custom_force.cpp into a plugin
// library (libfluid_whirlpool.so), loaded at run time with fluid::loadPluginLibrary or
// `fluid-run --plugin`. The plugin class itself is unchanged: a plugin library is ordinary
// plugin code plus this one macro. See docs/plugins.md.
#include "custom_force.h"

#include <fluid/plugin_abi.h>

// Defines fluid_plugin_abi_version, fluid_plugin_abi_details and fluid_register_plugins.
FLUID_PLUGIN_ENTRY(registry) {
    registerWhirlpool(registry);
}
