// fluid — 2D SPH liquid for games. The umbrella header: include this one.
#pragma once

#include <fluid/contacts.h>
#include <fluid/error.h>
#include <fluid/gameplay.h>
#include <fluid/groups.h>
#include <fluid/handle.h>
#include <fluid/material.h>
#include <fluid/plugin.h>
#include <fluid/query.h>
#include <fluid/registry.h>
#include <fluid/shape.h>
#include <fluid/surface_field.h>
#include <fluid/task.h>
#include <fluid/world.h>

#include <fluid/plugins/boundaries.h>
#include <fluid/plugins/builtin.h>
#include <fluid/plugins/forces.h>
