"""Force plugins written in Python: gravity in Python gives force.gravity's bits; parameters,
errors, expired views and the plugin's lifetime."""
import gc
import weakref

import numpy as np
import pytest

import fluid
from conftest import dam, fnv1a


class Gravity(fluid.ForcePlugin):
    """force.gravity in Python."""

    type = "test.gravity"
    params = (fluid.Param("gx", "m/s^2", 0.0, -1e3, 1e3, "x"),
              fluid.Param("gy", "m/s^2", -9.81, -1e3, 1e3, "y"))

    def __init__(self):
        self.calls = 0
        self.prepared = 0

    def prepare(self, ctx):
        self.prepared += 1
        assert ctx.frame_dt == pytest.approx(1 / 60)

    def apply(self, ctx):
        self.calls += 1
        gx, gy = ctx.params
        ctx.ax += np.float32(gx)
        ctx.ay += np.float32(gy)


def state(world):
    p = world.particles
    return fnv1a(*p.positions, *p.velocities)


@pytest.mark.parametrize("workers", [1, 2])
def test_python_gravity_same_bits_as_force_gravity(workers):
    with dam(workers) as reference, dam(workers, gravity=False) as python:
        plugin = Gravity()
        handle = python.add_force(plugin)
        handle["gy"] = -9.81
        assert handle.type == "test.gravity" and handle["gx"] == 0.0
        for _ in range(30):
            reference.step()
            python.step()
        assert state(reference) == state(python)
        assert plugin.prepared == 30 and plugin.calls >= 30


def test_params_reach_the_callback_and_are_range_checked():
    seen = []

    class Probe(fluid.ForcePlugin):
        type = "test.probe"
        params = (fluid.Param("k", "1/s", 2.0, 0.0, 10.0),)

        def apply(self, ctx):
            seen.append((ctx.params, ctx.begin, ctx.end, ctx.count, ctx.dt))

    with dam() as world:
        handle = world.add_force(Probe())
        world.step()
        handle["k"] = 7.5
        world.step()
        with pytest.raises(fluid.InvalidArgumentError):
            handle["k"] = 11.0
    assert seen[0][0] == (2.0,) and seen[-1][0] == (7.5,)
    assert seen[0][1] == 0 and seen[0][2] == seen[0][3] > 0 and seen[0][4] > 0


def test_range_views_match_the_world():
    got = {}

    class Copy(fluid.ForcePlugin):
        type = "test.copy"

        def apply(self, ctx):
            if got:
                return
            got["x"] = np.array(ctx.x)
            got["all_y"] = np.array(ctx.all_y)
            got["vx"] = np.array(ctx.vx)
            with pytest.raises(ValueError, match="read-only"):
                ctx.x[0] = 0.0

    with dam(gravity=False) as world:
        x0 = np.array(world.particles.x)
        world.add_force(Copy())
        world.step()
        # The first sub-step's particles, before any moved: the world's order at the start.
        assert np.array_equal(np.sort(got["x"]), np.sort(x0))
        assert got["all_y"].size == world.particle_count


def test_context_views_expire_after_the_call():
    kept = []

    class Keep(fluid.ForcePlugin):
        type = "test.keep"

        def apply(self, ctx):
            kept.append(ctx.ax)

    with dam() as world:
        world.add_force(Keep())
        world.step()
        with pytest.raises(fluid.ExpiredViewError, match="^ctx.ax: the world changed"):
            kept[0][0]


def test_exception_in_a_plugin_raises_from_step():
    class Broken(fluid.ForcePlugin):
        type = "test.broken"

        def apply(self, ctx):
            raise ZeroDivisionError("no force today")

    with dam() as world:
        world.add_force(Broken())
        with pytest.raises(fluid.PluginError) as error:
            world.step()
        assert str(error.value) == ("force plugin 'test.broken' raised during the step: "
                                    "ZeroDivisionError: no force today")
        assert isinstance(error.value.__cause__, ZeroDivisionError)
        assert world.time == pytest.approx(1 / 60)  # the step itself went on


def test_plugin_is_released_with_its_world():
    plugin = Gravity()
    ref = weakref.ref(plugin)
    world = dam(gravity=False)
    world.add_force(plugin)
    del plugin
    gc.collect()
    assert ref() is not None  # the world holds it
    world.step()
    world.close()
    gc.collect()
    assert ref() is None


def test_not_a_plugin(world):
    with pytest.raises(TypeError, match="expected a fluid.ForcePlugin instance, got int"):
        world.add_force(3)
