"""Worlds, materials, blobs, emitters, drains, sensors and plugins by name over fluid/c.h."""
import collections
import weakref

from ._fluid_c import ffi, lib
from ._views import Generation, guarded
from .errors import BY_STATUS, ClosedError, FluidError, PluginError

FRAME = 1.0 / 60.0


def check(status):
    """Raises the exception of a fluid_status other than FLUID_OK, with the C API's message."""
    if status != lib.FLUID_OK:
        message = ffi.string(lib.fluid_last_error()).decode("utf-8", "replace")
        cls = BY_STATUS.get(status, FluidError)
        name = ffi.string(lib.fluid_status_name(status)).decode()
        raise cls(message, status, name)


def call_out(ctype, function, *args):
    """Calls a C function whose last parameter receives its result (a `ctype` pointer, the C
    API's convention), checks its status and returns the result."""
    out = ffi.new(ctype)
    check(function(*args, out))
    return out[0]


def call_bytes(function, *args):
    """Calls a C function that hands out a fluid_bytes as its last parameter; returns them as
    Python bytes and frees the C copy."""
    b = ffi.new("fluid_bytes*")
    check(function(*args, b))
    try:
        return bytes(ffi.buffer(b.data, b.size))
    finally:
        lib.fluid_bytes_free(b)


def _camel(name):
    head, *rest = name.split("_")
    return head + "".join(w[:1].upper() + w[1:] for w in rest)


def _vec(v):
    x, y = v
    return (float(x), float(y))


# ---- what queries return --------------------------------------------------------------------

RayHit = collections.namedtuple(
    "RayHit", "point normal fraction starts_inside material particle index")
RayHit.__doc__ = """Where a ray first meets the liquid (World.ray_cast): point (m), the surface's
outward unit normal ((0, 0) when the ray starts inside), fraction (point = p1 + fraction
(p2 - p1); [0, 1]), starts_inside, the Material and the id (slot, generation, world) of the
nearest particle the field reaches from, and its index in the particle arrays until the world
changes."""

LiquidSample = collections.namedtuple(
    "LiquidSample",
    "in_liquid field density_ratio pressure velocity depth material neighbours fractions")
LiquidSample.__doc__ = """The liquid at a point (World.sample): in_liquid (where the renderer
draws it), the drawn field (1), density over rest density (1), pressure (Pa), velocity (m/s),
depth below the free surface straight up (m; 0 outside), the Material with the largest share
(None where no particle reaches), the particles whose kernel reaches the point (count), and
each material's share (a tuple by material index)."""


# ---- shapes ---------------------------------------------------------------------------------

class Shape:
    """A region: ``box(min, max)``, ``circle(center, radius)`` or ``polygon(points)`` (unit: m).
    A plain value; any thread."""

    __slots__ = ("kind", "a", "b", "points")

    def __init__(self, kind, a=None, b=None, points=None):
        self.kind, self.a, self.b, self.points = kind, a, b, points

    def _c(self, keep):
        """The fluid_shape (polygon vertices kept alive in `keep`)."""
        if self.kind == "box":
            return lib.fluid_box_shape(self.a, self.b)
        if self.kind == "circle":
            return lib.fluid_circle_shape(self.a, self.b)
        vertices = ffi.new("fluid_vec2[]", [tuple(_vec(p)) for p in self.points])
        keep.append(vertices)
        return lib.fluid_polygon_shape(vertices, len(self.points))

    def __repr__(self):
        if self.kind == "polygon":
            return f"polygon({self.points!r})"
        return f"{self.kind}({self.a!r}, {self.b!r})"


def box(min_corner, max_corner):
    """A box from its corners (unit: m; min < max on both axes, checked when used)."""
    return Shape("box", _vec(min_corner), _vec(max_corner))


def circle(center, radius):
    """A circle (unit: m; radius > 0, checked when used)."""
    return Shape("circle", _vec(center), float(radius))


def polygon(points):
    """A simple polygon of 3 to 256 vertices (unit: m; either winding, not crossing)."""
    return Shape("polygon", points=[_vec(p) for p in points])


# ---- ids --------------------------------------------------------------------------------------

class _Child:
    __slots__ = ("world", "id")

    def __init__(self, world, cid):
        self.world, self.id = world, cid

    @property
    def index(self):
        """Index in the order added (unit: index)."""
        return self.id.index

    def __eq__(self, other):
        return (type(self) is type(other) and self.world is other.world
                and self.id.index == other.id.index)

    def __hash__(self):
        return hash((type(self), id(self.world), self.id.index))

    def __repr__(self):
        return f"{type(self).__name__}({self.id.index})"


MATERIAL_FIELDS = ("mass", "rest_density", "viscosity", "stiffness", "smoothing_distance",
                   "kernel_particles", "surface_tension", "yield_stress", "consistency",
                   "flow_index", "shear_modulus")


class Material(_Child):
    """A material of a world (C++ fluid::Material). Thread rule: the world's."""

    @property
    def spacing(self):
        """Its particles' lattice spacing (unit: m)."""
        return call_out("float*", lib.fluid_world_spacing, self.world._ptr, self.id)

    def get(self):
        """Its fields as a dict: mass (kg), rest_density (kg/m^3), viscosity (Pa s),
        stiffness (J/kg), smoothing_distance (m), kernel_particles (count), surface_tension
        (m^3/(kg s^2)), yield_stress (Pa), consistency (Pa s^n), flow_index (1), shear_modulus
        (Pa), name (str)."""
        d = ffi.new("fluid_material_def*")
        check(lib.fluid_world_get_material(self.world._ptr, self.id, d))
        out = {f: getattr(d, f) for f in MATERIAL_FIELDS}
        out["name"] = ffi.string(d.name).decode() if d.name != ffi.NULL else ""
        return out

    def set(self, **fields):
        """Changes fields between steps, by the names of get() or the level files' camelCase
        names (ranges: docs/c_api.md). Raises InvalidArgumentError for a value out of range."""
        d = ffi.new("fluid_material_def*")
        check(lib.fluid_world_get_material(self.world._ptr, self.id, d))
        keep = _material_fields(d, fields)
        check(lib.fluid_world_set_material(self.world._ptr, self.id, d))
        del keep
        self.world._changed()


def _material_fields(d, fields):
    keep = []
    for key, value in fields.items():
        if key == "name":
            name = ffi.new("char[]", value.encode())
            keep.append(name)
            d.name = name
        else:
            check(lib.fluid_material_def_set(d, _camel(key).encode(), float(value)))
    return keep


class Plugin(_Child):
    """A plugin of a world (force or boundary), its parameters by name:
    ``plugin["strength"] = 30.0``; ``plugin["x"]``. Units and ranges: docs/plugins.md. Set
    between steps; thread rule: the world's."""

    @property
    def kind(self):
        """"force" or "boundary"."""
        return "force" if self.id.kind == lib.FLUID_PLUGIN_FORCE else "boundary"

    @property
    def type(self):
        """Its registered type name ("force.gravity")."""
        out = ffi.new("const char**")
        check(lib.fluid_plugin_type(self.world._ptr, self.id, out))
        return ffi.string(out[0]).decode()

    def __getitem__(self, name):
        return call_out("double*", lib.fluid_plugin_get_param, self.world._ptr, self.id,
                        name.encode())

    def __setitem__(self, name, value):
        check(lib.fluid_plugin_set_param(self.world._ptr, self.id, name.encode(),
                                         float(value)))

    def set(self, **params):
        """Sets several number parameters by name (unit and range: the parameter's)."""
        for name, value in params.items():
            self[name] = value

    def set_points(self, name, points):
        """Sets a point-list parameter (a polygon's vertices, a chain; unit: m; copied)."""
        array = ffi.new("fluid_vec2[]", [tuple(_vec(p)) for p in points])
        check(lib.fluid_plugin_set_points(self.world._ptr, self.id, name.encode(), array,
                                          len(points)))

    def __repr__(self):
        return f"Plugin({self.kind} {self.id.index})"


class Emitter(_Child):
    """An emitter (nozzle) of a world. Thread rule: the world's."""

    @property
    def emitted(self):
        """Particles it has made so far (unit: count)."""
        return call_out("uint32_t*", lib.fluid_world_emitted_count, self.world._ptr, self.id)


class Drain(_Child):
    """A drain of a world: removes the particles entering its shape."""


class Sensor(_Child):
    """A sensor of a world: what lies in its shape after each step. Thread rule: the world's."""

    def readings(self):
        """One dict per material index after the last step: count (particles), mass (kg),
        area (m^2), volume (m^3)."""
        ptr = ffi.new("const fluid_sensor_reading**")
        count = ffi.new("uint32_t*")
        check(lib.fluid_world_sensor_readings(self.world._ptr, self.id, ptr, count))
        return [{"count": r.count, "mass": r.mass, "area": r.area, "volume": r.volume}
                for r in (ptr[0][i] for i in range(count[0]))]


# ---- particle views -----------------------------------------------------------------------

class Particles:
    """The world's particle arrays as NumPy views of its memory (no copy), in the world's array
    order (which a step changes). Valid until the world changes (a step, a spawn, an added or
    removed particle): any read after that raises ExpiredViewError; ask ``world.particles``
    again, or copy (``numpy.array(p.x)``) what must outlive the step. Read-only. Thread rule:
    the world's."""

    def __init__(self, world):
        self._world = world
        self._generation = world._generation.value

    def _arrays(self, fn, n, ctype, dtype, what):
        world = self._world
        if world._generation.value != self._generation:
            from .errors import ExpiredViewError
            from ._views import _EXPIRED
            raise ExpiredViewError(_EXPIRED.format(what=what))
        ptrs = [ffi.new(f"const {ctype}**") for _ in range(n)]
        count = ffi.new("uint32_t*")
        check(fn(world._ptr, *ptrs, count))
        return [guarded(ffi, p[0], count[0], dtype, world._generation, what) for p in ptrs]

    def __len__(self):
        return self._world.particle_count

    @property
    def x(self):
        """Positions' x (unit: m; float32)."""
        return self._arrays(lib.fluid_world_positions, 2, "float", "f4", "particles.x")[0]

    @property
    def y(self):
        """Positions' y (unit: m; float32)."""
        return self._arrays(lib.fluid_world_positions, 2, "float", "f4", "particles.y")[1]

    @property
    def positions(self):
        """(x, y) (unit: m; two float32 arrays)."""
        return tuple(self._arrays(lib.fluid_world_positions, 2, "float", "f4",
                                  "particles.positions"))

    @property
    def velocities(self):
        """(vx, vy) (unit: m/s; two float32 arrays)."""
        return tuple(self._arrays(lib.fluid_world_velocities, 2, "float", "f4",
                                  "particles.velocities"))

    @property
    def vx(self):
        """Velocities' x (unit: m/s; float32)."""
        return self.velocities[0]

    @property
    def vy(self):
        """Velocities' y (unit: m/s; float32)."""
        return self.velocities[1]

    @property
    def density(self):
        """Densities after the last step (unit: kg/m^3; float32)."""
        return self._arrays(lib.fluid_world_densities, 1, "float", "f4",
                            "particles.density")[0]

    @property
    def pressure(self):
        """Pressures after the last step (unit: Pa; float32)."""
        return self._arrays(lib.fluid_world_pressures, 1, "float", "f4",
                            "particles.pressure")[0]

    @property
    def material(self):
        """Material indices (unit: index; uint16)."""
        return self._arrays(lib.fluid_world_material_indices, 1, "uint16_t", "u2",
                            "particles.material")[0]


# ---- worlds ---------------------------------------------------------------------------------

def _destroy_world(ptr):
    lib.fluid_world_destroy(ptr)


_SOLVERS = {"position_based": lib.FLUID_SOLVER_POSITION_BASED,
            "explicit": lib.FLUID_SOLVER_EXPLICIT}
_EOS = {"linear": lib.FLUID_EOS_LINEAR, "tait": lib.FLUID_EOS_TAIT}


class World:
    """A fluid world: particles, materials, plugins, emitters, drains and sensors.

    ``World(quality="game", workers=1, max_particles=None, solver="position_based", **fields)``
    makes one: quality "game" or "precise"; workers: threads that step it, the caller's
    included ([1, 256]; results are the same bits for any count); max_particles ([1, 2^26]);
    other fields by the C++ field tables' names, snake_case or camelCase (substeps,
    iterations, coarse_correction, depth (m)...; units and ranges: docs/c_api.md);
    equation_of_state ("linear", "tait") and sound_speed (m/s) for the explicit solver.

    A context manager: ``with World() as w:`` closes it at the end; close() frees it at once,
    and a world never closed is freed when collected. Thread rule: one thread at a time per
    world; different worlds from different threads at once.
    """

    def __init__(self, quality="game", workers=1, max_particles=None,
                 solver="position_based", equation_of_state=None, sound_speed=None,
                 **fields):
        d = ffi.new("fluid_world_def*", lib.fluid_default_world_def())
        check(lib.fluid_world_def_set_quality(d, quality.encode()))
        if solver not in _SOLVERS:
            raise ValueError(f"World: solver {solver!r}: expected one of {sorted(_SOLVERS)}")
        d.solver = _SOLVERS[solver]
        if equation_of_state is not None:
            d.equation_of_state = _EOS[equation_of_state]
        if sound_speed is not None:
            d.sound_speed = float(sound_speed)
        d.worker_count = int(workers)
        if max_particles is not None:
            check(lib.fluid_world_def_set(d, b"maxParticles", float(max_particles)))
        for key, value in fields.items():
            check(lib.fluid_world_def_set(d, _camel(key).encode(), float(value)))
        out = ffi.new("fluid_world**")
        check(lib.fluid_world_create(d, out))
        self._adopt(out[0], owner=None)

    @classmethod
    def _wrap(cls, ptr, owner):
        self = cls.__new__(cls)
        self._adopt(ptr, owner)
        return self

    def _adopt(self, ptr, owner):
        self._raw = ptr
        self._owner = owner  # a Level for a level's world: kept alive while this object lives
        self._generation = Generation()
        self._py_plugins = []
        self._finalizer = None if owner is not None else weakref.finalize(
            self, _destroy_world, ptr)

    @classmethod
    def load(cls, data, workers=0):
        """A world from save()'s bytes, with `workers` workers (0: as saved; else [1, 256]).
        Raises BadFileError for bytes that are not a whole snapshot, UnknownNameError for a
        Python plugin's type (not saved: only registered C types are made again)."""
        out = ffi.new("fluid_world**")
        data = bytes(data)
        check(lib.fluid_world_load(data, len(data), int(workers), out))
        return cls._wrap(out[0], None)

    @property
    def _ptr(self):
        if self._raw is None:
            raise ClosedError("the world is closed")
        if self._owner is not None and self._owner._raw is None:
            raise ClosedError("the world's level is closed")
        return self._raw

    def _changed(self):
        self._generation.bump()

    def close(self):
        """Frees the world now (its plugins' destroy callbacks run). Its arrays and ids are
        invalid after. Idempotent. A level's world closes with its level: close() raises
        ClosedError there. Not from inside the world's own step."""
        if self._owner is not None:
            raise ClosedError("a level's world closes with its level: close the level")
        if self._raw is not None:
            self._generation.bump()
            self._raw = None
            self._finalizer()
            self._py_plugins = []

    @property
    def closed(self):
        """True after close() (or the level's close())."""
        return self._raw is None or (self._owner is not None and self._owner._raw is None)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._owner is None:
            self.close()

    # ---- stepping and state ----

    def step(self, dt=FRAME):
        """Steps the world by one frame of `dt` (unit: s; (0, 1]): emitters, forces, the
        solver's sub-steps, boundaries, drains, sensors. Every particle array handed out so far
        expires. The GIL is released while it runs (other Python threads go on; Python force
        plugins take it back for their callbacks). Raises PluginError when a Python force
        plugin raised during it."""
        ptr = self._ptr
        self._generation.bump()
        status = lib.fluid_world_step(ptr, float(dt))
        self._generation.bump()
        self._raise_plugin_errors()
        check(status)

    def _raise_plugin_errors(self):
        for plugin in self._py_plugins:
            error = plugin._error
            if error is not None:
                plugin._error = None
                raise PluginError(f"force plugin {plugin.type!r} raised during the step: "
                                  f"{type(error).__name__}: {error}") from error

    @property
    def time(self):
        """Simulated time (unit: s)."""
        return call_out("double*", lib.fluid_world_time, self._ptr)

    @property
    def particle_count(self):
        """Particles alive (unit: count)."""
        return call_out("uint32_t*", lib.fluid_world_particle_count, self._ptr)

    @property
    def particles(self):
        """The particle arrays as NumPy views (class Particles): valid until the world
        changes."""
        self._ptr
        return Particles(self)

    def save(self):
        """The whole world as bytes (World.load makes it again and steps on bit for bit)."""
        return call_bytes(lib.fluid_world_save, self._ptr)

    # ---- materials and particles ----

    def add_material(self, preset="water", **fields):
        """Adds a material: a preset ("water", "yoghurt", "seed_yoghurt") with fields changed
        by name (see Material.get; name: a str). At most 65535 (LimitError)."""
        d = ffi.new("fluid_material_def*")
        check(lib.fluid_material_preset(preset.encode(), d))
        keep = _material_fields(d, fields)
        out = ffi.new("fluid_material_id*")
        check(lib.fluid_world_add_material(self._ptr, d, out))
        del keep
        return Material(self, out[0])

    @property
    def material_count(self):
        """Materials in the world (unit: count)."""
        return call_out("uint32_t*", lib.fluid_world_material_count, self._ptr)

    def material(self, index):
        """The material of index `index` (unit: index < material_count; not checked here)."""
        return Material(self, ffi.new("fluid_material_id*", (index, 0))[0])

    def spawn_blob(self, shape, material, velocity=(0.0, 0.0), lifetime=0.0, structure=0.0,
                   lattice_angle=0.0):
        """Fills `shape` with `material`'s particles on its lattice, moving at `velocity`
        (unit: m/s), each living `lifetime` (unit: s; 0 forever); `structure` for yield-stress
        materials (unit: 1; [0, 1]); the lattice turned counter-clockwise by `lattice_angle`
        (unit: rad; [-6.2832, 6.2832]: a layer on a slope filled along it has a flat top). A
        yield-stress material's circle is filled in rings (a round outline), starting at
        `lattice_angle`. Returns how many it made (unit: count). LimitError past max_particles. Particle arrays
        handed out so far expire."""
        keep = []
        d = ffi.new("fluid_blob_def*", lib.fluid_default_blob_def())
        d.shape = shape._c(keep)
        d.velocity = _vec(velocity)
        d.material = material.id
        d.lifetime = float(lifetime)
        d.structure = float(structure)
        out = ffi.new("uint32_t*")
        self._changed()
        check(lib.fluid_world_spawn_blob_turned(self._ptr, d, float(lattice_angle), out))
        return out[0]

    def add_particle(self, position, velocity, material):
        """Adds one particle (unit: m, m/s); returns its id (slot, generation, world)."""
        out = ffi.new("fluid_particle_id*")
        self._changed()
        check(lib.fluid_world_add_particle(self._ptr, _vec(position), _vec(velocity),
                                           material.id, out))
        return (out.slot, out.generation, out.world)

    def remove_particle(self, particle):
        """Removes a particle (an id from add_particle) now. StaleIdError for one gone."""
        self._changed()
        check(lib.fluid_world_remove_particle(self._ptr, particle))

    def count_in(self, shape):
        """Particles whose position lies in `shape` (unit: count). Between steps."""
        keep = []
        s = ffi.new("fluid_shape*", shape._c(keep))
        return call_out("uint32_t*", lib.fluid_world_count_in, self._ptr, s, ffi.NULL, 0)

    # ---- queries, rays, the liquid at a point (docs/queries.md) ----

    def query(self, shape):
        """The particles whose position lies in `shape`, in increasing index (the same for any
        number of workers): a list of ids (slot, generation, world), as add_particle returns.
        Between steps; from any number of threads at once."""
        keep = []
        s = ffi.new("fluid_shape*", shape._c(keep))
        found = ffi.new("uint32_t*")
        check(lib.fluid_world_query_ids(self._ptr, s, ffi.NULL, 0, found))
        n = found[0]
        ids = ffi.new("fluid_particle_id[]", max(n, 1))
        check(lib.fluid_world_query_ids(self._ptr, s, ids, n, found))
        return [(ids[k].slot, ids[k].generation, ids[k].world) for k in range(n)]

    def ray_cast(self, p1, p2, field_radius=2.0, threshold=0.6):
        """Where the segment p1 -> p2 (unit: m; finite) first enters the liquid as the renderer
        draws it (`field_radius`: a particle's reach over its spacing, [1, 4]; `threshold`:
        the field's level at the surface, [0.05, 4]; fluid::gl's defaults): a RayHit, or None
        when the ray misses the liquid. Between steps; from any number of threads at once."""
        field = ffi.new("fluid_surface_field*", (field_radius, threshold))
        hit = ffi.new("fluid_ray_hit*")
        check(lib.fluid_world_ray_cast(self._ptr, _vec(p1), _vec(p2), field, hit))
        if not hit.hit:
            return None
        return RayHit((hit.point.x, hit.point.y), (hit.normal.x, hit.normal.y), hit.fraction,
                      bool(hit.starts_inside), self.material(hit.material.index),
                      (hit.particle.slot, hit.particle.generation, hit.particle.world),
                      hit.index)

    def sample(self, point, field_radius=2.0, threshold=0.6):
        """The liquid at `point` (unit: m; finite), interpolated from the particles around it:
        a LiquidSample. `field_radius` and `threshold` as in ray_cast. Between steps; from any
        number of threads at once."""
        field = ffi.new("fluid_surface_field*", (field_radius, threshold))
        n = self.material_count
        fractions = ffi.new("float[]", max(n, 1))
        s = ffi.new("fluid_liquid_sample*")
        check(lib.fluid_world_sample(self._ptr, _vec(point), field, fractions, n, s))
        return LiquidSample(bool(s.in_liquid), s.field, s.density_ratio, s.pressure,
                            (s.velocity.x, s.velocity.y), s.depth,
                            self.material(s.material.index) if s.neighbours else None,
                            s.neighbours, tuple(fractions[k] for k in range(n)))

    # ---- plugins, emitters, drains, sensors ----

    def add_plugin(self, type, **params):
        """Adds a built-in or registered plugin by its type name ("force.gravity",
        "boundary.box", "force.pointer"...; docs/plugins.md) with parameters by name (the
        others at their defaults). UnknownNameError for an unknown type or parameter,
        InvalidArgumentError for a value out of range."""
        names = [ffi.new("char[]", k.encode()) for k in params]
        array = ffi.new("fluid_param[]", [(n, float(v)) for n, v in zip(names,
                                                                          params.values())])
        return Plugin(self, call_out("fluid_plugin_id*", lib.fluid_world_add_plugin, self._ptr,
                                     type.encode(), array, len(names)))

    def plugin_count(self, kind="force"):
        """Plugins of one kind ("force" or "boundary") in the world (unit: count)."""
        k = lib.FLUID_PLUGIN_FORCE if kind == "force" else lib.FLUID_PLUGIN_BOUNDARY
        return call_out("uint32_t*", lib.fluid_world_plugin_count, self._ptr, k)

    def plugin(self, index, kind="force"):
        """The plugin of `index` among the world's forces or boundaries."""
        k = lib.FLUID_PLUGIN_FORCE if kind == "force" else lib.FLUID_PLUGIN_BOUNDARY
        return Plugin(self, ffi.new("fluid_plugin_id*", (index, k, 0))[0])

    def add_force(self, plugin):
        """Adds a force plugin written in Python (a fluid.ForcePlugin); see docs/python.md for
        its callbacks and cost. Returns its Plugin id (parameters by name)."""
        from ._plugins import add_force
        return add_force(self, plugin)

    def add_emitter(self, position, direction, material, speed=1.0, width=0.05, rate=100.0,
                    max_count=0, lifetime=0.0, jitter=None, seed=None):
        """Adds a nozzle at `position` (unit: m) pointing along `direction` (unit: 1; not
        zero): exit speed (unit: m/s; [0.01, 100]), width (unit: m; [0, 100]), rate (unit:
        particles/s; [0, 1e6]), max_count (unit: count; 0 no limit), lifetime (unit: s; 0
        forever), jitter (unit: 1; [0, 0.5]), seed."""
        d = ffi.new("fluid_emitter_def*", lib.fluid_default_emitter_def())
        d.position, d.direction = _vec(position), _vec(direction)
        d.material = material.id
        d.speed, d.width, d.rate = float(speed), float(width), float(rate)
        d.max_count, d.lifetime = int(max_count), float(lifetime)
        if jitter is not None:
            d.jitter = float(jitter)
        if seed is not None:
            d.seed = int(seed)
        return Emitter(self, call_out("fluid_emitter_id*", lib.fluid_world_add_emitter,
                                      self._ptr, d))

    def add_drain(self, shape, material=None):
        """Adds a drain over `shape`: removes the particles entering it (only `material`'s when
        given)."""
        keep = []
        d = ffi.new("fluid_drain_def*")
        d.shape = shape._c(keep)
        if material is not None:
            d.only_material = True
            d.material = material.id
        return Drain(self, call_out("fluid_drain_id*", lib.fluid_world_add_drain, self._ptr, d))

    def add_sensor(self, shape):
        """Adds a sensor over `shape` (Sensor.readings after each step)."""
        keep = []
        return Sensor(self, call_out("fluid_sensor_id*", lib.fluid_world_add_sensor, self._ptr,
                                     shape._c(keep)))

    def removed_events(self):
        """The particles the last step removed, in order: dicts with position (m), velocity
        (m/s), material (index), cause ("drain", "lifetime", "out_of_range"), drain (index or
        None)."""
        ptr = ffi.new("const fluid_removed_event**")
        count = ffi.new("uint32_t*")
        check(lib.fluid_world_removed_events(self._ptr, ptr, count))
        causes = ("drain", "lifetime", "out_of_range")
        events = []
        for i in range(count[0]):
            e = ptr[0][i]
            cause = causes[e.cause] if 0 <= e.cause < 3 else str(e.cause)
            events.append({"position": (e.position.x, e.position.y),
                           "velocity": (e.velocity.x, e.velocity.y),
                           "material": e.material.index, "cause": cause,
                           "drain": e.drain.index if cause == "drain" else None})
        return events
