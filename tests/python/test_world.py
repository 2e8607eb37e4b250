"""Worlds through Python: the same bits as the C API alone, materials, plugins by name,
emitters, drains, sensors, saves, lifetimes."""
import gc
import os
import subprocess
import weakref

import numpy as np
import pytest

import fluid
from conftest import dam, fnv1a


@pytest.mark.parametrize("workers", [1, 2])
def test_dam_same_bits_as_c(workers):
    out = subprocess.run([os.environ["FLUID_PYTHON_DAM_C"], "45", str(workers)],
                         capture_output=True, text=True, check=True).stdout.split()
    with dam(workers) as world:
        for _ in range(45):
            world.step(1 / 60)
        p = world.particles
        x, y = p.positions
        vx, vy = p.velocities
        assert world.particle_count == int(out[0])
        assert f"{fnv1a(x, y, vx, vy):016x}" == out[1]


def test_dam_falls_and_stays_in_tank(world):
    start = np.array(world.particles.y).mean()
    for _ in range(60):
        world.step()
    x, y = world.particles.positions
    assert np.isfinite(x).all() and np.isfinite(y).all()
    assert y.mean() < start - 0.05
    assert x.max() > 0.5
    assert 0 <= x.min() and x.max() <= 1 and 0 <= y.min() and y.max() <= 1
    assert world.time == pytest.approx(1.0, abs=1e-6)


def test_material_fields_and_presets():
    with fluid.World() as world:
        water = world.add_material("water", viscosity=0.5, name="thick")
        yoghurt = world.add_material("yoghurt")
        assert world.material_count == 2
        got = water.get()
        assert got["name"] == "thick" and got["viscosity"] == np.float32(0.5)
        assert got["rest_density"] == 1000.0
        assert yoghurt.get()["yield_stress"] > 0
        water.set(restDensity=900)
        assert water.get()["rest_density"] == 900.0
        assert water.spacing > 0


def test_plugins_by_name_and_params(world):
    pointer = world.add_plugin("force.pointer", radius=0.1, strength=30.0)
    assert pointer.type == "force.pointer" and pointer.kind == "force"
    assert pointer["radius"] == pytest.approx(0.1)
    pointer.set(x=0.2, y=0.3, active=1)
    assert (pointer["x"], pointer["y"], pointer["active"]) == (pytest.approx(0.2),
                                                               pytest.approx(0.3), 1.0)
    assert world.plugin_count("force") == 2 and world.plugin_count("boundary") == 1
    assert world.plugin(0, "boundary").type == "boundary.box"


def test_emitter_drain_sensor_events():
    with fluid.World() as world:
        water = world.add_material("water")
        world.add_plugin("boundary.box", minX=0, minY=0, maxX=1, maxY=1)
        world.add_plugin("force.gravity", gy=-9.81)
        emitter = world.add_emitter((0.5, 0.8), (0, -1), water, speed=1.0, width=0.05,
                                    rate=300, max_count=100)
        sensor = world.add_sensor(fluid.box((0, 0), (1, 1)))
        drain = world.add_drain(fluid.box((0, 0), (1, 0.2)))
        removed = 0
        for _ in range(90):
            world.step()
            events = world.removed_events()
            assert all(e["cause"] == "drain" and e["drain"] == drain.index for e in events)
            removed += len(events)
        assert emitter.emitted == 100
        assert removed > 0
        assert world.particle_count == 100 - removed
        reading = sensor.readings()
        assert len(reading) == 1 and reading[0]["count"] == world.particle_count
        assert reading[0]["mass"] == pytest.approx(world.particle_count * water.get()["mass"],
                                                   rel=1e-5)


def test_save_and_load_step_on_same_bits(world):
    for _ in range(10):
        world.step()
    data = world.save()
    with fluid.World.load(data) as copy:
        for w in (world, copy):
            for _ in range(10):
                w.step()
        a, b = world.particles, copy.particles
        assert fnv1a(*a.positions, *a.velocities) == fnv1a(*b.positions, *b.velocities)


def test_particles_add_remove_count_in(world):
    water = world.material(0)
    n = world.particle_count
    pid = world.add_particle((0.8, 0.8), (0, 0), water)
    assert world.particle_count == n + 1
    assert world.count_in(fluid.circle((0.8, 0.8), 0.001)) == 1
    world.remove_particle(pid)
    assert world.particle_count == n
    with pytest.raises(fluid.StaleIdError):
        world.remove_particle(pid)


def test_close_is_idempotent_and_use_after_close_raises():
    world = dam()
    world.close()
    world.close()
    assert world.closed
    with pytest.raises(fluid.ClosedError, match="the world is closed"):
        world.step()
    with pytest.raises(fluid.ClosedError):
        world.particles


def test_forgotten_world_is_freed_by_the_collector():
    world = dam()
    finalizer = world._finalizer
    ref = weakref.ref(world)
    del world
    gc.collect()
    assert ref() is None and not finalizer.alive


def test_turned_blob_lies_along_its_slope():
    # A layer turned by -0.4 rad, filled on a lattice turned with it: 4 rows of particles, each
    # row at one distance under the layer's top edge (rows along x would leave steps).
    import math
    with fluid.World() as w:
        yoghurt = w.add_material("yoghurt")
        a = -0.4
        along, across = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
        base, length, thickness = (0.1, 0.6), 0.49, 0.0425
        corners = [base,
                   (base[0] + length * along[0], base[1] + length * along[1]),
                   (base[0] + length * along[0] + thickness * across[0],
                    base[1] + length * along[1] + thickness * across[1]),
                   (base[0] + thickness * across[0], base[1] + thickness * across[1])]
        n = w.spawn_blob(fluid.polygon(corners), yoghurt, lattice_angle=a)
        p = w.particles
        depth = [round((thickness - ((x - base[0]) * across[0] + (y - base[1]) * across[1]))
                       / 0.001) for x, y in zip(p.x, p.y)]
        assert len(set(depth)) == 4
        assert n == 4 * (n // 4)
        with pytest.raises(fluid.InvalidArgumentError) as error:
            w.spawn_blob(fluid.polygon(corners), yoghurt, lattice_angle=7.0)
        assert str(error.value) == ("spawnBlob: latticeAngle = 7 is out of range "
                                    "[-6.2832, 6.2832] (unit: rad)")
