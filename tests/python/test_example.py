"""python/examples/play_level.py headless (SDL_VIDEODRIVER=dummy): crates.json with the
scripted mouse (a push, a crate dropped), a PNG that shows the water in the tank."""
import os
import sys

import numpy as np
import pygame
import pytest

from conftest import LEVELS, SOURCE_DIR

sys.path.insert(0, os.path.join(SOURCE_DIR, "python", "examples"))
import play_level  # noqa: E402


def test_play_crates_headless():
    assert os.environ.get("SDL_VIDEODRIVER") == "dummy"
    png = os.path.join(os.environ.get("FLUID_TEST_OUT", "."), "play_level_crates.png")
    if os.path.exists(png):
        os.remove(png)
    player = play_level.run(os.path.join(LEVELS, "crates.json"), frames=70, png=png,
                            script=True, workers=2)
    try:
        world, level = player.world, player.level
        x, y = world.particles.positions
        assert not np.isnan(x).any() and not np.isnan(y).any()
        assert level.body_count == 10  # the file's nine and the dropped crate
        # The scripted button came up at half the window's width: x = 0.5 * 2.2 - 0.1 m.
        assert player.pointer["x"] == pytest.approx(1.0, abs=0.01)
        assert player.pointer["active"] == 0.0
        image = pygame.surfarray.array3d(pygame.image.load(png))
        water = np.all(image == play_level.WATER, axis=2)
        # The tank (0..2 m wide, water 0.12 m deep) in pixels: its lower part holds the water.
        cols, rows = player.view.to_screen(np.array([0.0, 2.0]), np.array([0.0, 0.3]))
        tank = water[int(cols[0]):int(cols[1]), int(rows[1]):int(rows[0])]
        # 2 m x 0.12 m of water at 800 / 2.2 px per m: about 16,000 pixels when at rest.
        assert tank.sum() > 8000
        assert water.sum() - tank.sum() < 0.05 * water.sum()
    finally:
        player.level.close()
