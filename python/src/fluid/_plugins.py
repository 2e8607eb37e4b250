"""Force plugins written in Python, through the C API's fluid_world_add_force."""
import numpy as np

from ._core import Plugin, check
from ._fluid_c import ffi, lib
from ._views import Generation, GuardedArray

# Plugins a world holds: kept alive until the world lets them go (their destroy callback).
_live = {}


class Param:
    """A parameter a Python plugin declares: name (printable, at most 256 bytes), unit (text,
    "m/s^2"), default, minimum and maximum (in that unit), description (one line). The world
    checks the range when it is set (Plugin["name"] = value); callbacks read ctx.params."""

    __slots__ = ("name", "unit", "default", "minimum", "maximum", "description")

    def __init__(self, name, unit="", default=0.0, minimum=-1e30, maximum=1e30,
                 description=""):
        self.name, self.unit, self.description = name, unit, description
        self.default, self.minimum, self.maximum = float(default), float(minimum), float(maximum)


class ForcePlugin:
    """Base of a force plugin written in Python: subclass it, set ``type`` (its name in
    messages, "game.whirlpool"; 1 to 256 printable bytes) and ``params`` (a sequence of Param),
    and define ``apply(self, ctx)`` (and optionally ``prepare(self, ctx)``); add an instance
    with ``world.add_force(instance)``.

    apply(ctx) adds accelerations (unit: m/s^2) to particles ctx.begin..ctx.end: ctx.ax and
    ctx.ay are writable float32 views of that range only; ctx.x, ctx.y (m), ctx.vx, ctx.vy
    (m/s), ctx.material (index) the same range, read-only; ctx.all_x ... all particles;
    ctx.dt the sub-step (s), ctx.time (s), ctx.params the parameter values (tuple, the
    declarations' order). Called once per sub-step per range, on the world's worker threads
    (several at once on disjoint ranges with workers > 1; each call holds the GIL, so they take
    turns): write only your range and keep the result independent of the split. The views
    expire when the call returns (ExpiredViewError after).

    prepare(ctx) runs once per step before the sub-steps, on the stepping thread:
    ctx.frame_dt (s), ctx.time (s), ctx.sample_spacing (m), ctx.support_radius (m),
    ctx.params.

    An exception in a callback cannot stop the step (C has no way to): the plugin adds nothing
    more during that step, and world.step() raises PluginError with it as the cause.
    """

    type = "python.force"
    params = ()

    def prepare(self, ctx):
        """Once per step before the sub-steps (see the class)."""

    def apply(self, ctx):
        """Adds accelerations to ctx.ax, ctx.ay (see the class)."""
        raise NotImplementedError


class StepContext:
    """What prepare() is told about the step: frame_dt (s), time (s), sample_spacing (m),
    support_radius (m), params (tuple)."""

    __slots__ = ("frame_dt", "time", "sample_spacing", "support_radius", "params")


def _array(pointer, begin, n, dtype, generation, what, writable=False):
    if n == 0:
        a = np.empty(0, dtype=dtype).view(GuardedArray)
    else:
        size = np.dtype(dtype).itemsize
        a = np.frombuffer(ffi.buffer(pointer + begin, n * size), dtype=dtype).view(GuardedArray)
    a._fluid_guard = (generation, generation.value, what)
    if not writable:
        a.flags.writeable = False
    return a


class ForceContext:
    """What apply() reads and writes (see ForcePlugin): views valid during the call only."""

    __slots__ = ("_c", "_generation", "begin", "end", "count", "dt", "time", "params",
                 "_ax", "_ay")

    def __init__(self, c, begin, end, param_count):
        self._c, self.begin, self.end = c, begin, end
        self._generation = Generation()
        self.count, self.dt, self.time = c.count, c.dt, c.time
        self.params = tuple(ffi.unpack(c.params, param_count)) if param_count else ()
        self._ax = self._ay = None

    def _range(self, name, dtype="f4", writable=False):
        return _array(getattr(self._c, name), self.begin, self.end - self.begin, dtype,
                      self._generation, "ctx." + name, writable)

    def _all(self, name, dtype="f4"):
        return _array(getattr(self._c, name), 0, self.count, dtype, self._generation,
                      "ctx.all_" + name)

    @property
    def ax(self):
        """Accelerations' x to add to (unit: m/s^2; float32; this call's range, writable)."""
        if self._ax is None:
            self._ax = self._range("ax", writable=True)
        return self._ax

    @ax.setter
    def ax(self, value):
        if value is not self._ax:  # `ctx.ax += g` assigns the same array back
            raise AttributeError("ctx.ax is a view: write into it (ctx.ax[...] = ...)")

    @property
    def ay(self):
        """Accelerations' y to add to (unit: m/s^2; float32; this call's range, writable)."""
        if self._ay is None:
            self._ay = self._range("ay", writable=True)
        return self._ay

    @ay.setter
    def ay(self, value):
        if value is not self._ay:
            raise AttributeError("ctx.ay is a view: write into it (ctx.ay[...] = ...)")

    x = property(lambda self: self._range("px"), doc="Positions' x (m), the range.")
    y = property(lambda self: self._range("py"), doc="Positions' y (m), the range.")
    vx = property(lambda self: self._range("vx"), doc="Velocities' x (m/s), the range.")
    vy = property(lambda self: self._range("vy"), doc="Velocities' y (m/s), the range.")
    material = property(lambda self: self._range("material", "u2"),
                        doc="Material indices, the range.")
    all_x = property(lambda self: self._all("px"), doc="Positions' x (m), all particles.")
    all_y = property(lambda self: self._all("py"), doc="Positions' y (m), all particles.")
    all_vx = property(lambda self: self._all("vx"), doc="Velocities' x (m/s), all particles.")
    all_vy = property(lambda self: self._all("vy"), doc="Velocities' y (m/s), all particles.")


class _Holder:
    __slots__ = ("plugin", "type", "param_count", "keep", "handle", "_error")

    def __init__(self, plugin):
        self.plugin = plugin
        self.type = plugin.type
        self.param_count = len(plugin.params)
        self._error = None


@ffi.def_extern()
def _fluid_py_force_prepare(user, context):
    holder = ffi.from_handle(user)
    if holder._error is not None:
        return
    try:
        ctx = StepContext()
        ctx.frame_dt, ctx.time = context.frame_dt, context.time
        ctx.sample_spacing, ctx.support_radius = context.sample_spacing, context.support_radius
        ctx.params = (tuple(ffi.unpack(context.params, holder.param_count))
                      if holder.param_count else ())
        holder.plugin.prepare(ctx)
    except BaseException as error:  # noqa: B036 - nothing may unwind into C
        holder._error = error


@ffi.def_extern()
def _fluid_py_force_apply(user, context, begin, end):
    holder = ffi.from_handle(user)
    if holder._error is not None:
        return
    ctx = ForceContext(context, begin, end, holder.param_count)
    try:
        holder.plugin.apply(ctx)
    except BaseException as error:  # noqa: B036 - nothing may unwind into C
        if holder._error is None:
            holder._error = error
    finally:
        ctx._generation.bump()


@ffi.def_extern()
def _fluid_py_force_destroy(user):
    _live.pop(id(ffi.from_handle(user)), None)


def add_force(world, plugin):
    """world.add_force's work (see World.add_force)."""
    if not isinstance(plugin, ForcePlugin):
        raise TypeError("add_force: expected a fluid.ForcePlugin instance, got "
                        f"{type(plugin).__name__}")
    holder = _Holder(plugin)
    keep = [ffi.new("char[]", str(plugin.type).encode())]
    decls = ffi.new("fluid_param_decl[]", len(plugin.params))
    for d, p in zip(decls, plugin.params):
        strings = [ffi.new("char[]", s.encode()) for s in (p.name, p.unit, p.description)]
        keep += strings
        d.name, d.unit, d.description = strings
        d.default_value, d.min_value, d.max_value = p.default, p.minimum, p.maximum
    holder.keep = keep + [decls]
    holder.handle = ffi.new_handle(holder)
    d = ffi.new("fluid_force_plugin_def*", lib.fluid_default_force_plugin_def())
    d.type = keep[0]
    d.user = holder.handle
    d.params, d.param_count = decls, len(plugin.params)
    if type(plugin).prepare is not ForcePlugin.prepare:
        d.prepare = lib._fluid_py_force_prepare
    d.apply = lib._fluid_py_force_apply
    d.destroy = lib._fluid_py_force_destroy
    out = ffi.new("fluid_plugin_id*")
    check(lib.fluid_world_add_force(world._ptr, d, out))  # on failure destroy is not called
    _live[id(holder)] = holder
    world._py_plugins.append(holder)
    return Plugin(world, out[0])
