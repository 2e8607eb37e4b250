// custom_force.h: the whirlpool force plugin of examples/custom_force.cpp.
#pragma once

#include <fluid/registry.h>

/// Registers the example's "force.whirlpool" plugin type into `registry` (parameters cx, cy,
/// strength, radius, pull). Throws fluid::Error if the type is already registered.
void registerWhirlpool(fluid::Registry& registry);
