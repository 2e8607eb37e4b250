// fluid — registration of the built-in plugins.
#include <fluid/plugins/builtin.h>

namespace fluid {

void registerBuiltinPlugins(Registry& registry) {
    registerBuiltinForces(registry);
    registerBuiltinBoundaries(registry);
}

} // namespace fluid
