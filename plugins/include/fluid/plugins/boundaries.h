// fluid — every built-in boundary plugin.
#pragma once

#include <fluid/plugins/box_container.h>
#include <fluid/plugins/chain.h>
#include <fluid/plugins/circle.h>
#include <fluid/plugins/kinematic_shape.h>
#include <fluid/plugins/polygon.h>
