"""Errors: each C status raises its class, with the C API's status, name and message."""
import os

import pytest

import fluid
from conftest import LEVELS


def test_unknown_plugin(world):
    with pytest.raises(fluid.UnknownNameError) as error:
        world.add_plugin("force.nope")
    e = error.value
    assert (e.status, e.status_name) == (4, "FLUID_ERROR_UNKNOWN_NAME")
    assert isinstance(e, LookupError) and isinstance(e, fluid.FluidError)
    assert str(e) == MESSAGES["unknown_plugin"]


def test_unknown_parameter(world):
    with pytest.raises(fluid.UnknownNameError) as error:
        world.add_plugin("force.gravity", gz=1.0)
    assert str(error.value) == MESSAGES["unknown_parameter"]


def test_out_of_range_step(world):
    with pytest.raises(fluid.InvalidArgumentError) as error:
        world.step(0.0)
    e = error.value
    assert (e.status, e.status_name) == (1, "FLUID_ERROR_INVALID_ARGUMENT")
    assert isinstance(e, ValueError)
    assert str(e) == MESSAGES["step_zero"]


def test_out_of_range_param(world):
    gravity = world.plugin(0)
    with pytest.raises(fluid.InvalidArgumentError) as error:
        gravity["gy"] = float("nan")
    assert str(error.value) == MESSAGES["param_nan"]


def test_unknown_quality_and_preset():
    with pytest.raises(fluid.UnknownNameError) as error:
        fluid.World(quality="cinematic")
    assert str(error.value) == MESSAGES["quality"]
    with fluid.World() as world:
        with pytest.raises(fluid.UnknownNameError) as error:
            world.add_material("honey")
        assert str(error.value) == MESSAGES["preset"]


def test_limit():
    with fluid.World(max_particles=10) as world:
        water = world.add_material("water")
        with pytest.raises(fluid.LimitError) as error:
            world.spawn_blob(fluid.box((0, 0), (0.2, 0.2)), water)
        assert error.value.status == 7 and str(error.value) == MESSAGES["limit"]
        assert world.particle_count == 0


def test_missing_level_file():
    with pytest.raises(fluid.FileIOError) as error:
        fluid.Level.load("/nonexistent/level.json")
    assert error.value.status == 6 and isinstance(error.value, OSError)
    assert str(error.value) == MESSAGES["io"]


def test_malformed_level():
    with pytest.raises(fluid.BadFileError) as error:
        fluid.Level.parse('{"version": 1, "world": {"frameRate": "fast"}}', file="bad.json")
    assert error.value.status == 5 and str(error.value) == MESSAGES["bad_file"]


def test_unknown_level_name():
    with fluid.Level.load(os.path.join(LEVELS, "dam_break.json")) as level:
        with pytest.raises(fluid.UnknownNameError) as error:
            level.find_material("lava")
        assert str(error.value) == MESSAGES["find"]


# The C API's messages (the C++ library's text), exactly.
MESSAGES = {
    "unknown_plugin": "unknown plugin type 'force.nope'; known: force.gravity "
                      "force.point_gravity force.vortex force.wind force.pointer "
                      "force.explosion force.damping boundary.box boundary.polygon "
                      "boundary.chain boundary.circle",
    "unknown_parameter": "plugin 'force.gravity': unknown parameter 'gz'; known: gx gy",
    "step_zero": "World::step: frameDt = 0 s is out of range; expected a finite value in "
                 "(0, 1] (typically 1/60)",
    "param_nan": "plugin 'force.gravity': parameter 'gy' = nan is not finite; expected "
                 "[-1000, 1000] (unit: m/s^2)",
    "quality": "fluid_world_def_set_quality: unknown quality 'cinematic' (expected game or "
               "precise)",
    "preset": "fluid_material_preset: unknown preset 'honey' (expected water, yoghurt or "
              "seed_yoghurt)",
    "limit": "spawnBlob: particle cap exceeded: the blob needs about 361 particles; "
             "maxParticles = 10",
    "io": "loadLevel: cannot open '/nonexistent/level.json': No such file or directory",
    "bad_file": "bad.json:1:39: at /world/frameRate: expected a number in [1, 1000] "
                "(unit: Hz), got a string",
    "find": "fluid_level_find_material: the level has no material named 'lava'",
}


def test_every_status_has_its_class():
    # The classes take their numbers and names from fluid/c.h: each status 1..9 raises its own
    # class, named as fluid_status_name names it.
    assert sorted(fluid.errors.BY_STATUS) == list(range(1, 10))
    for status, cls in fluid.errors.BY_STATUS.items():
        assert cls.status == status
        assert cls.status_name.startswith("FLUID_ERROR_")
        assert issubclass(cls, fluid.FluidError)
    assert fluid.errors.BY_STATUS[6] is fluid.FileIOError
    assert fluid.FileIOError.status_name == "FLUID_ERROR_IO"
