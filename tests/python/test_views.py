"""The particle arrays: zero copy (the C API's own pointers), read-only, refused once the world
has changed, copies kept."""
import copy
import pickle

import numpy as np
import pytest

import fluid
from fluid import _ffi as ffi
from fluid import _lib as lib

EXPIRED = ("particles.x: the world changed since this array was taken (a step, a spawn, a "
           "removal...), so its memory may have moved or been freed; ask the world again "
           "(world.particles) or copy the array (numpy.array(a)) before changing the world")


def c_pointers(world, fn, n):
    ptrs = [ffi.new("const float**") for _ in range(n)]
    count = ffi.new("uint32_t*")
    assert fn(world._ptr, *ptrs, count) == lib.FLUID_OK
    return [int(ffi.cast("uintptr_t", p[0])) for p in ptrs], count[0]


def test_views_are_the_c_api_memory(world):
    world.step()
    p = world.particles
    (cx, cy), n = c_pointers(world, lib.fluid_world_positions, 2)
    (cvx, cvy), _ = c_pointers(world, lib.fluid_world_velocities, 2)
    (cd,), _ = c_pointers(world, lib.fluid_world_densities, 1)
    x, y = p.positions
    vx, vy = p.velocities
    assert [a.ctypes.data for a in (x, y, vx, vy, p.density)] == [cx, cy, cvx, cvy, cd]
    assert len(x) == n == world.particle_count and x.dtype == np.float32
    assert p.material.dtype == np.uint16 and (p.material == 0).all()
    assert not x.flags.owndata and not x.flags.writeable


def test_views_are_read_only(world):
    x = world.particles.x
    with pytest.raises(ValueError, match="read-only"):
        x[0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        x += 1.0


def test_views_refused_after_a_step(world):
    p = world.particles
    x = p.x
    head = x[:10]
    kept = np.array(x)
    also_kept = x.copy()
    world.step()
    for read in (lambda: x[0], lambda: x.sum(), lambda: np.mean(x), lambda: repr(x),
                 lambda: list(x), lambda: x + 1, lambda: x.tolist(), lambda: x.tobytes(),
                 lambda: x.copy(), lambda: copy.copy(x), lambda: pickle.dumps(x),
                 lambda: head[0], lambda: str(head)):
        with pytest.raises(fluid.ExpiredViewError) as error:
            read()
        assert str(error.value) == EXPIRED
    with pytest.raises(fluid.ExpiredViewError, match="^particles.y: the world changed"):
        p.y
    # Copies own their memory and stay.
    assert kept.sum() == also_kept.sum() and type(also_kept) is np.ndarray
    # Asked again, the arrays are good, and the new ones are the C API's current memory.
    (cx, _), _ = c_pointers(world, lib.fluid_world_positions, 2)
    assert world.particles.x.ctypes.data == cx
    assert float(world.particles.x.sum()) != 0.0


@pytest.mark.parametrize("change", ["spawn", "add", "remove"])
def test_views_refused_after_particles_change(world, change):
    x = world.particles.x
    water = world.material(0)
    if change == "spawn":
        world.spawn_blob(fluid.circle((0.7, 0.7), 0.05), water)
    elif change == "add":
        world.add_particle((0.7, 0.7), (0, 0), water)
    else:
        pid = world.add_particle((0.7, 0.7), (0, 0), water)
        x = world.particles.x
        world.remove_particle(pid)
    with pytest.raises(fluid.ExpiredViewError):
        x.max()


def test_views_refused_after_close():
    world = fluid.World()
    world.add_material("water")
    world.spawn_blob(fluid.box((0, 0), (0.1, 0.1)), world.material(0))
    x = world.particles.x
    world.close()
    with pytest.raises(fluid.ExpiredViewError):
        x[0]


def test_views_in_numpy_expressions_while_valid(world):
    p = world.particles
    x, y = p.positions
    assert np.allclose(np.hypot(x, y), np.sqrt(x * x + y * y))
    assert x[x > 0.1].size > 0 and float(x.max()) <= 0.25
    assert type(x + 1) is np.ndarray  # results are plain arrays that own their memory
