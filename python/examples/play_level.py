#!/usr/bin/env python3
"""Plays a level file in a pygame window: the mouse pushes the water (the built-in
"force.pointer" plugin follows the pointer while the left button is held) and a right click (or
the space bar) drops a crate where the pointer is (a Box2D body, in levels that have bodies,
e.g. levels/crates.json). The liquid is drawn as discs, the bodies as outlines.

    python3 python/examples/play_level.py levels/crates.json
    SDL_VIDEODRIVER=dummy python3 python/examples/play_level.py levels/crates.json \\
        --frames 120 --script --png out.png          (headless: scripted mouse, a PNG)

Needs the fluid package (pip install ./python) and Debian's python3-pygame.
"""
import argparse
import json
import math
import os
import sys

import numpy as np
import pygame

import fluid

WATER = (40, 110, 230)
BACKGROUND = (245, 245, 240)
BODY = (120, 80, 40)
CRATE = (0.08, 0.08)  # the dropped crate's width and height (unit: m)


class View:
    """World (m) to screen (pixels): the level's extent, y up, with a margin."""

    def __init__(self, lo, hi, width):
        self.lo = np.array(lo, dtype=np.float64)
        span = np.array(hi, dtype=np.float64) - self.lo
        self.scale = width / span[0]
        self.size = (width, int(math.ceil(span[1] * self.scale)))

    def to_screen(self, x, y):
        """Pixel columns and rows of points (unit: m; arrays)."""
        return ((x - self.lo[0]) * self.scale, self.size[1] - (y - self.lo[1]) * self.scale)

    def to_world(self, px, py):
        """The point (m) under a pixel."""
        return (px / self.scale + self.lo[0], (self.size[1] - py) / self.scale + self.lo[1])


def level_extent(doc, world):
    """The tank's box (a "boundary.box" plugin of the file), else the liquid's extent."""
    for plugin in doc.get("plugins", []):
        if plugin.get("type") == "boundary.box":
            p = plugin.get("params", {})
            return (p.get("minX", 0), p.get("minY", 0)), (p.get("maxX", 1), p.get("maxY", 1))
    x, y = world.particles.positions
    return (float(x.min()) - 0.1, float(y.min()) - 0.1), (float(x.max()) + 0.1,
                                                          float(y.max()) + 0.4)


def body_outlines(doc):
    """Each file body's fixtures by name: lists of local polygons (m) or (radius, centre)."""
    out = {}
    for body in doc.get("bodies", []):
        shapes = []
        for f in body.get("fixtures", []):
            c = f.get("center", [0, 0])
            if f.get("shape") == "box":
                w, h = f["width"] / 2, f["height"] / 2
                shapes.append([(c[0] - w, c[1] - h), (c[0] + w, c[1] - h), (c[0] + w, c[1] + h),
                               (c[0] - w, c[1] + h)])
            elif f.get("shape") == "circle":
                shapes.append((f["radius"], tuple(c)))
            elif f.get("shape") == "polygon":
                shapes.append([tuple(v) for v in f["vertices"]])
        out[body.get("name", "")] = shapes
    return out


class Player:
    """The level, its pointer plugin, its crates and the drawing."""

    def __init__(self, path, width=800, workers=0):
        with open(path, encoding="utf-8") as f:
            self.doc = json.load(f)
        self.level = fluid.Level.load(path, workers=workers)
        self.world = self.level.world
        lo, hi = level_extent(self.doc, self.world)
        margin = 0.05 * (hi[0] - lo[0])
        self.view = View((lo[0] - margin, lo[1] - margin), (hi[0] + margin, hi[1] + margin),
                         width)
        self.pointer = self.world.add_plugin("force.pointer", radius=0.1, strength=30.0)
        self.outlines = body_outlines(self.doc)
        self.crates = {}  # body index -> outline
        self.liquid = self.world.material(0)
        self.radius = max(2, int(round(0.75 * self.liquid.spacing * self.view.scale)))
        r = self.radius
        self.disc = [(dx, dy) for dx in range(-r, r + 1) for dy in range(-r, r + 1)
                     if dx * dx + dy * dy <= r * r]

    def handle(self, event):
        """Mouse and keys: left button pushes, right button or space drops a crate."""
        if event.type in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEMOTION, pygame.MOUSEBUTTONUP):
            x, y = self.view.to_world(*event.pos)
            self.pointer.set(x=x, y=y)
        if event.type == pygame.MOUSEBUTTONDOWN and event.button == 1:
            self.pointer["active"] = 1.0
        elif event.type == pygame.MOUSEBUTTONUP and event.button == 1:
            self.pointer["active"] = 0.0
        elif (event.type == pygame.MOUSEBUTTONDOWN and event.button == 3) or (
                event.type == pygame.KEYDOWN and event.key == pygame.K_SPACE):
            self.drop_crate(self.pointer["x"], self.pointer["y"])

    def drop_crate(self, x, y):
        """A crate of half the liquid's density at (x, y) (unit: m); no-op without bodies."""
        if self.level.body_count == 0:
            return
        w, h = CRATE
        index = self.level.add_body(fluid.box((x - w / 2, y - h / 2), (x + w / 2, y + h / 2)),
                                    density=0.5 * self.level.areal_density(self.liquid))
        self.crates[index] = [[(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2),
                               (-w / 2, h / 2)]]

    def draw(self, surface):
        """The liquid as discs of its colour, the bodies as outlines."""
        x, y = self.world.particles.positions
        cols, rows = self.view.to_screen(x, y)
        cols = cols.astype(np.int32)
        rows = rows.astype(np.int32)
        width, height = self.view.size
        pixels = np.empty((width, height, 3), dtype=np.uint8)
        pixels[:] = BACKGROUND
        for dx, dy in self.disc:
            c, r = cols + dx, rows + dy
            inside = (c >= 0) & (c < width) & (r >= 0) & (r < height)
            pixels[c[inside], r[inside]] = WATER
        pygame.surfarray.blit_array(surface, pixels)
        file_bodies = len(self.doc.get("bodies", []))
        for i, body in enumerate(self.level.bodies):
            shapes = self.crates.get(i) if i >= file_bodies else self.outlines.get(body.name)
            if shapes:
                self._draw_body(surface, body, shapes)

    def _draw_body(self, surface, body, shapes):
        ca, sa = math.cos(body.angle), math.sin(body.angle)
        bx, by = body.position
        for shape in shapes:
            if isinstance(shape, tuple):  # (radius, centre)
                radius, (cx, cy) = shape
                px, py = self.view.to_screen(bx + ca * cx - sa * cy, by + sa * cx + ca * cy)
                pygame.draw.circle(surface, BODY, (px, py), radius * self.view.scale, 2)
            else:
                points = [self.view.to_screen(bx + ca * vx - sa * vy, by + sa * vx + ca * vy)
                          for vx, vy in shape]
                pygame.draw.polygon(surface, BODY, points, 2)


def scripted_events(frame, view, player):
    """The headless run's mouse: a push across the tank from frame 20 to 60, a crate at 30."""
    span = np.array(view.size) / view.scale

    def at(fx, fy):
        return (int((fx * span[0]) * view.scale), int(view.size[1] - fy * span[1] * view.scale))
    events = []
    if frame == 20:
        events.append(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=at(0.1, 0.1), button=1))
    elif 20 < frame < 60:
        events.append(pygame.event.Event(pygame.MOUSEMOTION, pos=at(0.1 + 0.01 * (frame - 20),
                                                                     0.1),
                                         rel=(0, 0), buttons=(1, 0, 0)))
    elif frame == 60:
        events.append(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=at(0.5, 0.1), button=1))
    if frame == 30:  # the crate, then the pointer back where the push is
        events.append(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=at(0.5, 0.6), button=3))
        events.append(pygame.event.Event(pygame.MOUSEMOTION, pos=at(0.2, 0.1), rel=(0, 0),
                                         buttons=(1, 0, 0)))
    return events


def run(path, frames=0, png=None, script=False, width=800, workers=0):
    """Plays `path` for `frames` frames (0: until the window closes) on `workers` threads
    (0: the file's); `script` drives the mouse itself; `png` saves the last frame. Returns the
    Player (its level stays open)."""
    pygame.init()
    player = Player(path, width, workers)
    surface = pygame.display.set_mode(player.view.size)
    pygame.display.set_caption(f"fluid: {os.path.basename(path)}")
    clock = pygame.time.Clock()
    frame = 0
    while frames == 0 or frame < frames:
        events = pygame.event.get()
        if script:
            events += scripted_events(frame, player.view, player)
        if any(e.type == pygame.QUIT for e in events):
            break
        for event in events:
            player.handle(event)
        player.level.step()
        player.draw(surface)
        pygame.display.flip()
        if not script:
            clock.tick(player.level.frame_rate)
        frame += 1
    if png:
        pygame.image.save(surface, png)
    pygame.quit()
    return player


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("level", help="a level file (levels/crates.json)")
    parser.add_argument("--frames", type=int, default=0, help="frames to play (0: until closed)")
    parser.add_argument("--png", help="save the last frame to this PNG")
    parser.add_argument("--script", action="store_true", help="drive the mouse by a script")
    parser.add_argument("--workers", type=int, default=0, help="threads (0: the file's)")
    args = parser.parse_args()
    player = run(args.level, args.frames, args.png, args.script, workers=args.workers)
    x, y = player.world.particles.positions
    print(f"play_level: {args.level}: {player.world.particle_count} particles, "
          f"{player.level.body_count} bodies, t = {player.world.time:.3f} s, "
          f"{int(np.isnan(x).sum() + np.isnan(y).sum())} NaN")
    player.level.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
