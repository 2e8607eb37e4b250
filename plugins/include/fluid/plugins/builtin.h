// fluid — registration of the built-in plugins.
#pragma once

#include <fluid/registry.h>

namespace fluid {

/// Registers every built-in plugin type (forces "force.*" and boundaries "boundary.*") into
/// `registry`. Explicit by design: a static library drops self-registering objects nobody
/// references. Throws `fluid::Error` if a type is already registered. Thread rule: as
/// `Registry::add`.
void registerBuiltinPlugins(Registry& registry);

/// Registers the built-in force plugins only (see `registerBuiltinPlugins`).
void registerBuiltinForces(Registry& registry);

/// Registers the built-in boundary plugins only (see `registerBuiltinPlugins`).
void registerBuiltinBoundaries(Registry& registry);

} // namespace fluid
