"""Queries, ray casts and the liquid at a point through Python (World.query, World.ray_cast,
World.sample): a layer of water at rest read the way a game reads it, and the exact errors."""
import math

import pytest

import fluid


@pytest.fixture(scope="module")
def layer():
    """Water 0.1 m deep across a 1 x 1 m tank, after 1 s under gravity (the game preset)."""
    world = fluid.World(quality="game")
    water = world.add_material("water")
    world.add_plugin("boundary.box", minX=0, minY=0, maxX=1, maxY=1)
    world.add_plugin("force.gravity", gx=0, gy=-9.81)
    world.spawn_blob(fluid.box((0, 0), (1, 0.1)), water)
    for _ in range(60):
        world.step()
    yield world
    world.close()


@pytest.mark.parametrize("x", [0.2, 0.5, 0.8])
def test_a_ray_down_stops_on_the_surface(layer, x):
    hit = layer.ray_cast((x, 0.9), (x, 0.0))
    assert hit is not None and not hit.starts_inside
    spacing = layer.material(0).spacing
    # On the segment at its fraction, at the layer's top within two spacings, facing up.
    assert hit.point[0] == pytest.approx(x, abs=1e-6)
    assert hit.point[1] == pytest.approx(0.9 - 0.9 * hit.fraction, abs=1e-5)
    assert abs(hit.point[1] - 0.1) < 2 * spacing
    assert hit.normal[1] > 0.8 and math.hypot(*hit.normal) == pytest.approx(1.0, abs=1e-4)
    # The particle it names is a live one, at that index of the arrays, of water.
    assert hit.material == layer.material(0)
    assert hit.index < layer.particle_count
    x_all, y_all = layer.particles.positions
    assert math.hypot(x_all[hit.index] - hit.point[0], y_all[hit.index] - hit.point[1]) < \
        2 * spacing
    assert hit.particle in layer.query(fluid.circle(hit.point, 2 * spacing))


def test_a_ray_in_the_air_misses(layer):
    assert layer.ray_cast((0.5, 0.9), (0.5, 0.5)) is None


def test_a_ray_from_inside_starts_there(layer):
    hit = layer.ray_cast((0.5, 0.03), (0.5, 0.9))
    assert hit.starts_inside and hit.fraction == 0.0 and hit.point == pytest.approx((0.5, 0.03))


def test_the_liquid_at_a_point(layer):
    deep = layer.sample((0.5, 0.02))
    assert deep.in_liquid and deep.material == layer.material(0)
    assert deep.neighbours > 10 and deep.fractions == pytest.approx((1.0,))
    assert deep.depth == pytest.approx(0.08, abs=2 * layer.material(0).spacing)
    assert deep.pressure > 0 and 0.8 < deep.density_ratio < 1.2
    air = layer.sample((0.5, 0.8))
    assert not air.in_liquid and air.material is None and air.neighbours == 0
    assert air.depth == 0.0 and air.fractions == (0.0,)


def test_a_query_names_the_particles_in_a_shape(layer):
    every = layer.query(fluid.box((0, 0), (1, 1)))
    assert len(every) == layer.particle_count == len(set(every))
    left = fluid.box((0, 0), (0.5, 1))
    assert len(layer.query(left)) == layer.count_in(left) > 0
    assert layer.query(fluid.circle((0.5, 0.8), 0.1)) == []


def test_a_queried_particle_can_be_removed():
    with fluid.World() as world:
        water = world.add_material("water")
        world.spawn_blob(fluid.box((0, 0), (0.1, 0.1)), water)
        before = world.particle_count
        first = world.query(fluid.box((0, 0), (1, 1)))[0]
        world.remove_particle(first)
        assert world.particle_count == before - 1
        with pytest.raises(fluid.StaleIdError):
            world.remove_particle(first)


def test_bad_rays_and_fields_are_refused_with_the_c_message(layer):
    with pytest.raises(fluid.InvalidArgumentError) as e:
        layer.ray_cast((math.nan, 0), (0, 0))
    assert str(e.value) == "fluid_world_ray_cast: p1 = (nan, 0) is not finite (unit: m)"
    with pytest.raises(fluid.InvalidArgumentError) as e:
        layer.sample((0.5, 0.5), field_radius=9)
    assert str(e.value) == ("fluid_world_sample: field->field_radius = 9 is out of range "
                            "[1, 4] (unit: 1)")
