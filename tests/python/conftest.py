"""Shared helpers of the python tests (run by ctest in the venv python.install makes)."""
import os

import numpy as np
import pytest

import fluid

SOURCE_DIR = os.environ.get("FLUID_SOURCE_DIR",
                            os.path.dirname(os.path.dirname(os.path.dirname(__file__))))
LEVELS = os.path.join(SOURCE_DIR, "levels")


def fnv1a(*arrays):
    """FNV-1a (64 bits) of the arrays' bytes in turn, as tests/python/dam_c.c computes it."""
    h = 14695981039346656037
    for a in arrays:
        for byte in np.asarray(a).tobytes():
            h = ((h ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def dam(workers=1, gravity=True):
    """tests/python/dam_c.c's dam: game preset, water 0.25 x 0.5 m in a 1 x 1 m tank."""
    world = fluid.World(quality="game", workers=workers)
    water = world.add_material("water")
    world.add_plugin("boundary.box", minX=0, minY=0, maxX=1, maxY=1)
    if gravity:
        world.add_plugin("force.gravity", gx=0, gy=-9.81)
    world.spawn_blob(fluid.box((0, 0), (0.25, 0.5)), water)
    return world


@pytest.fixture
def world():
    with dam() as w:
        yield w
