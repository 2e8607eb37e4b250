"""Level files (docs/levels.md) and their Box2D bodies (docs/c_api_bodies.md)."""
import collections
import os
import weakref

from ._core import (Drain, Emitter, Material, Plugin, Sensor, World, _vec, call_bytes, call_out,
                    check)
from ._fluid_c import ffi, lib
from .errors import ClosedError

Body = collections.namedtuple("Body", "name position angle")
Body.__doc__ = ("A Box2D body of a level: name (\"\" for an added one), position (unit: m; "
                "(x, y)), angle (unit: rad).")

_GOALS = ("none", "pending", "won", "lost")
_BODY_TYPES = {"static": lib.FLUID_BODY_STATIC, "kinematic": lib.FLUID_BODY_KINEMATIC,
               "dynamic": lib.FLUID_BODY_DYNAMIC}


def _options(workers, max_particles):
    o = ffi.new("fluid_level_options*", lib.fluid_default_level_options())
    o.worker_count, o.max_particles = int(workers), int(max_particles)
    return o


class Level:
    """A level file loaded: its world (``level.world``), named objects, Box2D bodies, goal.

    Make one with Level.load(path), Level.parse(text), Level.load_save(path) or
    Level.read_save(data); options: workers (unit: count; 0 the file's, else [1, 256]) and
    max_particles (unit: count; 0 the file's). A context manager; close() frees it with its
    world and bodies, and a level never closed is freed when collected (its world object keeps
    it alive). Thread rule: one thread at a time per level (its world included).
    """

    def __init__(self, *_args, **_kwargs):
        raise TypeError("use Level.load, Level.parse, Level.load_save or Level.read_save")

    @classmethod
    def _make(cls, fn, *args):
        out = ffi.new("fluid_level**")
        check(fn(*args, out))
        self = cls.__new__(cls)
        self._raw = out[0]
        self._finalizer = weakref.finalize(self, lib.fluid_level_destroy, out[0])
        w = ffi.new("fluid_world**")
        check(lib.fluid_level_world(self._raw, w))
        self._world = World._wrap(w[0], owner=self)
        return self

    @classmethod
    def load(cls, path, workers=0, max_particles=0):
        """Loads a level file (JSON). BadFileError ("FILE:LINE:COLUMN: at /json/path:
        message"), UnknownNameError, FileIOError for one that cannot be read."""
        return cls._make(lib.fluid_level_load, os.fsencode(path),
                         _options(workers, max_particles))

    @classmethod
    def parse(cls, text, file="level.json", workers=0, max_particles=0):
        """Parses a level from its text (str or bytes); `file` names it in messages."""
        data = text.encode() if isinstance(text, str) else bytes(text)
        return cls._make(lib.fluid_level_parse, data, len(data), file.encode(),
                         _options(workers, max_particles))

    @classmethod
    def load_save(cls, path, workers=0, max_particles=0):
        """Loads a level save file (Level.save's)."""
        return cls._make(lib.fluid_level_load_save, os.fsencode(path),
                         _options(workers, max_particles))

    @classmethod
    def read_save(cls, data, file="save", workers=0, max_particles=0):
        """Loads a level save from Level.save_bytes()'s bytes; `file` names it in messages."""
        data = bytes(data)
        return cls._make(lib.fluid_level_read_save, data, len(data), file.encode(),
                         _options(workers, max_particles))

    @property
    def _ptr(self):
        if self._raw is None:
            raise ClosedError("the level is closed")
        return self._raw

    def close(self):
        """Frees the level, its world and bodies now; its world object and ids are invalid
        after. Idempotent. Not from inside the level's own step."""
        if self._raw is not None:
            self._world._changed()
            self._raw = None
            self._finalizer()
            self._world._py_plugins = []

    @property
    def closed(self):
        """True after close()."""
        return self._raw is None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def world(self):
        """The level's world (a World that the level owns: read and change it, step it with
        level.step(); it cannot be closed on its own)."""
        self._ptr
        return self._world

    def step(self):
        """Steps one frame of the level's frame rate: the world, the Box2D bodies, the goal.
        The world's particle arrays expire. PluginError when a Python force plugin raised."""
        ptr = self._ptr
        self._world._changed()
        status = lib.fluid_level_step(ptr)
        self._world._changed()
        self._world._raise_plugin_errors()
        check(status)

    @property
    def frame_rate(self):
        """Frames per second (unit: 1/s)."""
        return call_out("float*", lib.fluid_level_frame_rate, self._ptr)

    def save(self, path):
        """Saves the level (its file's text, the world, the bodies) to `path` (load_save reads
        it). FileIOError when it cannot be written."""
        check(lib.fluid_level_save(self._ptr, os.fsencode(path)))

    def save_bytes(self):
        """The level's save as bytes (read_save reads them)."""
        return call_bytes(lib.fluid_level_save_bytes, self._ptr)

    @property
    def goal(self):
        """(state, value): state "none", "pending", "won" or "lost"; value in the goal's unit
        (count, fraction or m^3)."""
        state = ffi.new("fluid_goal_state*")
        value = ffi.new("double*")
        check(lib.fluid_level_goal(self._ptr, state, value))
        return _GOALS[state[0]], value[0]

    def _find(self, fn, ctype, cls, name):
        out = ffi.new(ctype)
        check(fn(self._ptr, name.encode(), out))
        return cls(self._world, out[0])

    def find_material(self, name):
        """The material the file names `name`; UnknownNameError naming it otherwise."""
        return self._find(lib.fluid_level_find_material, "fluid_material_id*", Material, name)

    def find_emitter(self, name):
        """The emitter the file names `name` (UnknownNameError otherwise)."""
        return self._find(lib.fluid_level_find_emitter, "fluid_emitter_id*", Emitter, name)

    def find_drain(self, name):
        """The drain the file names `name` (UnknownNameError otherwise)."""
        return self._find(lib.fluid_level_find_drain, "fluid_drain_id*", Drain, name)

    def find_sensor(self, name):
        """The sensor the file names `name` (UnknownNameError otherwise)."""
        return self._find(lib.fluid_level_find_sensor, "fluid_sensor_id*", Sensor, name)

    def find_plugin(self, name):
        """The plugin the file names `name` (UnknownNameError otherwise)."""
        return self._find(lib.fluid_level_find_plugin, "fluid_plugin_id*", Plugin, name)

    # ---- bodies ----

    @property
    def body_count(self):
        """Box2D bodies: the file's, then the added ones (unit: count)."""
        return call_out("uint32_t*", lib.fluid_level_body_count, self._ptr)

    def body(self, index):
        """Body `index` (unit: index < body_count; StaleIdError past it) as a Body."""
        name = ffi.new("const char**")
        position = ffi.new("fluid_vec2*")
        angle = ffi.new("float*")
        check(lib.fluid_level_body(self._ptr, index, name, position, angle))
        return Body(ffi.string(name[0]).decode(), (position.x, position.y), angle[0])

    @property
    def bodies(self):
        """Every body, as Body values, in index order."""
        return [self.body(i) for i in range(self.body_count)]

    def areal_density(self, material):
        """A material's liquid as Box2D weighs bodies (unit: kg/m^2): a body of half this
        floats half submerged."""
        return call_out("float*", lib.fluid_level_areal_density, self._ptr, material.id)

    def add_body(self, shape, type="dynamic", density=0.0, friction=0.4, position=None,
                 angle=0.0, velocity=(0.0, 0.0), angular_velocity=0.0):
        """Adds a Box2D body (a level whose file declares bodies only: RefusedError otherwise)
        with one fixture `shape` (a box or circle centred on the body, or a convex polygon of 3
        to 8 vertices around `position`; unit: m); type "static", "kinematic" or "dynamic";
        density (unit: kg/m^2; > 0 for a dynamic body: see areal_density), friction (unit: 1;
        >= 0), angle (unit: rad), velocity (unit: m/s), angular_velocity (unit: rad/s).
        Returns its body index. Between steps."""
        keep = []
        d = ffi.new("fluid_body_def*", lib.fluid_default_body_def())
        d.type = _BODY_TYPES[type]
        d.shape = shape._c(keep)
        if position is not None:
            d.position = _vec(position)
        d.angle, d.density, d.friction = float(angle), float(density), float(friction)
        d.velocity, d.angular_velocity = _vec(velocity), float(angular_velocity)
        return call_out("uint32_t*", lib.fluid_level_add_body, self._ptr, d)

    def remove_body(self, index):
        """Removes body `index` with its joints; the later bodies move down one index."""
        check(lib.fluid_level_remove_body(self._ptr, index))

    def set_body_velocity(self, index, velocity, angular_velocity=0.0):
        """Sets a body's velocity (unit: m/s) and angular velocity (unit: rad/s)."""
        check(lib.fluid_level_set_body_velocity(self._ptr, index, _vec(velocity),
                                                float(angular_velocity)))

    def set_gravity(self, gravity):
        """Sets gravity (unit: m/s^2; finite) for the liquid and the bodies alike."""
        check(lib.fluid_level_set_gravity(self._ptr, _vec(gravity)))
