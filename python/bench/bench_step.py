#!/usr/bin/env python3
"""What stepping from Python costs: the dam of bench/fluid_c_bench.cpp (a water block twice as
tall as wide in a box four blocks wide, gravity, the game preset) stepped through World.step and
through the bare C call (lib.fluid_world_step, what C code does), in alternating rounds on the
same thread count; they must end with the same bits. Then a force plugin written in Python
(gravity) against the built-in force.gravity: its cost per particle per sub-step and per call.

    python3 python/bench/bench_step.py [--particles 4000] [--frames 120] [--rounds 6]
                                       [--threads 1] [--c-bench build/release/bench/fluid-c-bench]

With --c-bench, fluid-c-bench runs the same dam (C against C++) first, and the Python figure
is also given over C++ (C / C++ times Python / C).
"""
import argparse
import math
import re
import subprocess
import time

import numpy as np

import fluid
from fluid import _lib as lib

FRAME = 1.0 / 60.0


class PyGravity(fluid.ForcePlugin):
    """force.gravity written in Python: ctx.ay += gy over its range."""

    type = "bench.gravity"
    params = (fluid.Param("gx", "m/s^2", 0.0, -1e3, 1e3), fluid.Param("gy", "m/s^2", -9.81,
                                                                        -1e3, 1e3))

    def __init__(self):
        self.calls = 0
        self.seconds = 0.0  # inside apply, summed

    def apply(self, ctx):
        start = time.perf_counter()
        self.calls += 1
        gx, gy = ctx.params
        ctx.ax += np.float32(gx)
        ctx.ay += np.float32(gy)
        self.seconds += time.perf_counter() - start


def dam(particles, threads, python_gravity=None):
    """The dam of fluid_c_bench.cpp's damFor (about `particles` particles)."""
    world = fluid.World(quality="game", workers=threads)
    water = world.add_material("water")
    columns = round(math.sqrt(particles / 2.0))
    width = np.float32(columns * world.material(0).spacing)
    height = np.float32(2 * width)
    world.add_plugin("boundary.box", minX=0, minY=0, maxX=float(np.float32(4 * width)),
                     maxY=float(np.float32(1.5 * height)))
    if python_gravity is None:
        world.add_plugin("force.gravity", gx=0.0, gy=-9.81)
    else:
        world.add_force(python_gravity)
    world.spawn_blob(fluid.box((0, 0), (float(width), float(height))), water)
    return world


def timed(step, frames):
    start = time.perf_counter()
    for _ in range(frames):
        step()
    return time.perf_counter() - start


def callback_cost(count, reps=2000):
    """Seconds per call of a Python force plugin's apply through the C trampoline (what the
    world's step calls), on `count` particles, without a step around it: min of 5 runs."""
    from fluid import _ffi as ffi
    from fluid._plugins import _Holder

    holder = _Holder(PyGravity())
    handle = ffi.new_handle(holder)
    arrays = [ffi.new("float[]", count) for _ in range(6)]
    material = ffi.new("uint16_t[]", count)
    params = ffi.new("double[]", [0.0, -9.81])
    ctx = ffi.new("fluid_force_context*", {
        "px": arrays[0], "py": arrays[1], "vx": arrays[2], "vy": arrays[3],
        "material": material, "count": count, "ax": arrays[4], "ay": arrays[5],
        "dt": FRAME / 4, "time": 0.0, "params": params})
    apply = lib._fluid_py_force_apply
    best = min(timed(lambda: apply(handle, ctx, 0, count), reps) for _ in range(5)) / reps
    if holder._error is not None:
        raise holder._error
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=int, default=4000)
    parser.add_argument("--frames", type=int, default=120)
    parser.add_argument("--rounds", type=int, default=6)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--c-bench", help="path of fluid-c-bench, to run the same dam first")
    args = parser.parse_args()

    c_over_cpp = None
    if args.c_bench:
        out = subprocess.run([args.c_bench, "--particles", str(args.particles), "--frames",
                              str(args.frames), "--rounds", str(args.rounds), "--threads",
                              str(args.threads), "--quality", "game"],
                             capture_output=True, text=True, check=True).stdout
        print(out.strip())
        c_over_cpp = float(re.search(r"C / C\+\+ ([0-9.]+)", out).group(1))

    wrapped, bare = dam(args.particles, args.threads), dam(args.particles, args.threads)
    ptr = bare._ptr
    c_step = lib.fluid_world_step
    py_s = c_s = 0.0
    for _ in range(args.rounds):
        py_s += timed(lambda: wrapped.step(FRAME), args.frames)
        c_s += timed(lambda: c_step(ptr, FRAME), args.frames)
    bare._changed()
    same = all(np.array_equal(a, b) for a, b in zip(
        (*wrapped.particles.positions, *wrapped.particles.velocities),
        (*bare.particles.positions, *bare.particles.velocities)))
    n = wrapped.particle_count
    frames = args.frames * args.rounds
    print(f"bench_step: dam {n} particles, game, {args.threads} thread(s), {args.rounds} "
          f"rounds of {args.frames} frames")
    print(f"bench_step: C call {1e3 * c_s / frames:.3f} ms/frame, World.step "
          f"{1e3 * py_s / frames:.3f} ms/frame, Python / C {py_s / c_s:.4f}"
          + (f", Python / C++ {py_s / c_s * c_over_cpp:.4f}" if c_over_cpp else "")
          + f", same bits: {'yes' if same else 'no'}")

    # The wrapper alone, without the noise of a 10 ms step: World.step against the bare call on
    # an empty world (no particles: the step is a few microseconds), many times.
    empty_py, empty_c = fluid.World(), fluid.World()
    empty_py.add_material("water")
    empty_c.add_material("water")
    empty_ptr = empty_c._ptr
    reps = 20000
    wrap_s = min(timed(lambda: empty_py.step(FRAME), reps) for _ in range(3))
    bare_s = min(timed(lambda: c_step(empty_ptr, FRAME), reps) for _ in range(3))
    overhead = (wrap_s - bare_s) / reps
    print(f"bench_step: World.step's own cost {1e6 * overhead:.2f} us per step (empty world: "
          f"{1e6 * wrap_s / reps:.2f} us against the bare call's {1e6 * bare_s / reps:.2f} us), "
          f"{100 * overhead / (c_s / frames):.3f} % of the dam's frame")
    empty_py.close()
    empty_c.close()

    plugin = PyGravity()
    python, builtin = dam(args.particles, args.threads, plugin), dam(args.particles,
                                                                      args.threads)
    python.step()  # warm up, then count from zero
    builtin.step()
    plugin.calls, plugin.seconds = 0, 0.0
    plugin_s = builtin_s = 0.0
    for _ in range(args.rounds):
        plugin_s += timed(python.step, args.frames)
        builtin_s += timed(builtin.step, args.frames)
    same_plugin = all(np.array_equal(a, b) for a, b in zip(
        (*python.particles.positions, *python.particles.velocities),
        (*builtin.particles.positions, *builtin.particles.velocities)))
    calls = plugin.calls
    extra = plugin_s - builtin_s
    substeps = calls / frames / args.threads if args.threads == 1 else None
    per_call = extra / calls
    print(f"bench_step: Python gravity {1e3 * plugin_s / frames:.3f} ms/frame, force.gravity "
          f"{1e3 * builtin_s / frames:.3f} ms/frame: {1e6 * per_call:.1f} us per call "
          f"({calls / frames:.1f} calls a frame), "
          + (f"{1e9 * extra / frames / substeps / n:.2f} ns per particle per sub-step, "
             if substeps else "")
          + f"same bits: {'yes' if same_plugin else 'no'}; inside apply "
          f"{1e6 * plugin.seconds / calls:.1f} us per call")
    small, large = callback_cost(1000), callback_cost(n)
    per_particle = (large - small) / (n - 1000)
    print(f"bench_step: Python gravity's apply alone: {1e6 * small:.2f} us per call on 1000 "
          f"particles, {1e6 * large:.2f} us on {n}: {1e6 * (small - 1000 * per_particle):.2f} us "
          f"per call plus {1e9 * per_particle:.2f} ns per particle; per particle per sub-step "
          f"at {n}: {1e9 * large / n:.2f} ns")
    for w in (wrapped, bare, python, builtin):
        w.close()
    return 0 if same and same_plugin else 1


if __name__ == "__main__":
    raise SystemExit(main())
