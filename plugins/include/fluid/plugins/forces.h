// fluid — every built-in force plugin.
#pragma once

#include <fluid/plugins/damping_zone.h>
#include <fluid/plugins/explosion.h>
#include <fluid/plugins/gravity.h>
#include <fluid/plugins/point_gravity.h>
#include <fluid/plugins/pointer.h>
#include <fluid/plugins/vortex.h>
#include <fluid/plugins/wind.h>
