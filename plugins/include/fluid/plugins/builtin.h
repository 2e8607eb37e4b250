// fluid — registration of the built-in plugins.
#pragma once

#include <fluid/registry.h>

namespace fluid {

/// Registers every built-in plugin type ("force.gravity", "boundary.box") into `registry`.
/// Explicit by design: a static library drops self-registering objects nobody references.
/// Throws `fluid::Error` if a type is already registered. Thread rule: as `Registry::add`.
void registerBuiltinPlugins(Registry& registry);

} // namespace fluid
