"""fluid: 2D SPH liquid for games, from Python (docs/python.md).

A layer over fluid's C API (libfluid_c.so, fluid/c.h) built with cffi: World, materials,
blobs, emitters, drains, sensors, plugins by name, force plugins written in Python, level files
with their Box2D bodies; particle arrays as zero-copy NumPy views that expire when the world
changes; every failing call raises the fluid.errors class of its C status with the C message.

    import fluid
    with fluid.World(quality="game") as world:
        water = world.add_material("water")
        world.add_plugin("boundary.box", minX=0, minY=0, maxX=1, maxY=1)
        world.add_plugin("force.gravity", gy=-9.81)
        world.spawn_blob(fluid.box((0, 0), (0.3, 0.5)), water)
        for _ in range(60):
            world.step(1 / 60)
        print(world.particles.y.mean())

Thread rule (the C API's): a world or level is used by one thread at a time; different worlds
from different threads at once.
"""
from ._core import (FRAME, Drain, Emitter, LiquidSample, Material, Particles, Plugin, RayHit,
                    Sensor, Shape, World, box, circle, polygon)
from ._fluid_c import ffi as _ffi  # noqa: F401 (the C layer, for tests and tools)
from ._fluid_c import lib as _lib
from ._level import Body, Level
from ._plugins import ForceContext, ForcePlugin, Param, StepContext
from ._views import GuardedArray
from .errors import (BadFileError, ClosedError, ExpiredViewError, FileIOError, FluidError,
                     InvalidArgumentError, LimitError, NullArgumentError, OutOfMemoryError,
                     PluginError, RefusedError, StaleIdError, UnknownNameError)

C_API_VERSION = _lib.fluid_version()
"""The library's C API version (major * 100 + minor)."""

if C_API_VERSION // 100 != _lib.FLUID_C_VERSION_MAJOR:
    raise ImportError(f"fluid: libfluid_c.so has C API {C_API_VERSION}, this package was "
                      f"built for major version {_lib.FLUID_C_VERSION_MAJOR}")

__version__ = "1.0.0"

__all__ = [
    "FRAME", "World", "Level", "Body", "Material", "Plugin", "Emitter", "Drain", "Sensor",
    "Particles", "RayHit", "LiquidSample", "Shape", "box", "circle", "polygon", "ForcePlugin",
    "ForceContext",
    "StepContext", "Param", "GuardedArray", "FluidError", "InvalidArgumentError",
    "NullArgumentError", "StaleIdError", "UnknownNameError", "BadFileError", "FileIOError",
    "LimitError", "OutOfMemoryError", "RefusedError", "PluginError", "ExpiredViewError",
    "ClosedError", "C_API_VERSION",
]
