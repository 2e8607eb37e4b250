"""Levels: load, step, bodies, save and load back, the world's lifetime under its level."""
import gc
import os

import numpy as np
import pytest

import fluid
from conftest import LEVELS, fnv1a


def test_dam_break_level_steps():
    with fluid.Level.load(os.path.join(LEVELS, "dam_break.json")) as level:
        world = level.world
        assert level.frame_rate == 60.0
        n = world.particle_count
        y0 = np.array(world.particles.y).mean()
        for _ in range(30):
            level.step()
        assert world.particle_count == n and world.particles.y.mean() < y0
        assert level.goal == ("none", 0.0)
        assert level.find_material("water").index == 0
        assert level.find_plugin("tank").type == "boundary.box"


def test_crates_bodies_and_an_added_crate():
    with fluid.Level.load(os.path.join(LEVELS, "crates.json"), workers=2) as level:
        names = [b.name for b in level.bodies]
        assert names[:3] == ["tank", "cork", "pine"] and len(names) == 9
        water = level.find_material("water")
        areal = level.areal_density(water)
        assert areal > 0
        index = level.add_body(fluid.box((0.95, 0.4), (1.05, 0.48)), density=2.0 * areal)
        assert index == 9 and level.body(index).name == ""
        assert level.body(index).position == pytest.approx((1.0, 0.44))
        for _ in range(40):
            level.step()
        assert level.body(index).position[1] < 0.2  # twice the water's density: it sank
        with pytest.raises(fluid.StaleIdError):
            level.body(10)
        level.remove_body(index)
        assert level.body_count == 9


def test_level_save_loads_back_to_the_same_bits(tmp_path):
    with fluid.Level.load(os.path.join(LEVELS, "dam_break.json")) as level:
        for _ in range(10):
            level.step()
        path = tmp_path / "dam.save"
        level.save(path)
        data = level.save_bytes()
        with fluid.Level.load_save(path) as a, fluid.Level.read_save(data) as b:
            for lv in (level, a, b):
                for _ in range(10):
                    lv.step()
            hashes = {fnv1a(*lv.world.particles.positions) for lv in (level, a, b)}
            assert len(hashes) == 1


def test_level_world_lifetime():
    level = fluid.Level.load(os.path.join(LEVELS, "dam_break.json"))
    world = level.world
    with pytest.raises(fluid.ClosedError, match="a level's world closes with its level"):
        world.close()
    del level
    gc.collect()
    world.step()  # the world object keeps its level alive
    owner = world._owner
    owner.close()
    with pytest.raises(fluid.ClosedError, match="the world's level is closed"):
        world.particle_count
    with pytest.raises(fluid.ClosedError, match="the level is closed"):
        owner.step()


def test_python_plugin_in_a_level_world():
    class Wind(fluid.ForcePlugin):
        type = "test.wind"

        def apply(self, ctx):
            ctx.ax += np.float32(5.0)

    with fluid.Level.load(os.path.join(LEVELS, "dam_break.json")) as level:
        x0 = np.array(level.world.particles.x).mean()
        level.world.add_force(Wind())
        for _ in range(20):
            level.step()
        assert level.world.particles.x.mean() > x0
