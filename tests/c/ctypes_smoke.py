#!/usr/bin/env python3
"""Another language through libfluid_c.so: Python's ctypes (the standard library only) loads the
shared library, builds the dam (water, a tank and gravity by their registry names), steps it a
second and reads the positions: the water fell and spread, none left the tank. Also a failing
call: its status and message.

    python3 tests/c/ctypes_smoke.py build/release/c/libfluid_c.so
"""
import ctypes as C
import sys

lib = C.CDLL(sys.argv[1])


class Vec2(C.Structure):
    _fields_ = [("x", C.c_float), ("y", C.c_float)]


class WorldDef(C.Structure):
    _fields_ = [("solver", C.c_int32), ("substeps", C.c_uint32), ("iterations", C.c_uint32),
                ("viscosity_interval", C.c_uint32), ("coarse_correction", C.c_float),
                ("vorticity", C.c_float), ("shear_constraint", C.c_uint32),
                ("equation_of_state", C.c_int32), ("sound_speed", C.c_float),
                ("depth", C.c_float), ("courant", C.c_float), ("max_substeps", C.c_uint32),
                ("max_particles", C.c_uint32), ("worker_count", C.c_uint32)]


class MaterialDef(C.Structure):
    _fields_ = [(name, C.c_float) for name in (
        "mass", "rest_density", "viscosity", "stiffness", "smoothing_distance",
        "kernel_particles", "surface_tension", "yield_stress", "consistency", "flow_index",
        "shear_modulus")] + [("name", C.c_char_p)]


class MaterialId(C.Structure):
    _fields_ = [("index", C.c_uint32), ("world", C.c_uint32)]


class PluginId(C.Structure):
    _fields_ = [("index", C.c_uint32), ("kind", C.c_uint32), ("world", C.c_uint32)]


class Param(C.Structure):
    _fields_ = [("name", C.c_char_p), ("value", C.c_double)]


class Shape(C.Structure):
    _fields_ = [("type", C.c_int32), ("center", Vec2), ("half_extents", Vec2),
                ("radius", C.c_float), ("vertices", C.POINTER(Vec2)),
                ("vertex_count", C.c_uint32)]


class BlobDef(C.Structure):
    _fields_ = [("shape", Shape), ("velocity", Vec2), ("material", MaterialId),
                ("lifetime", C.c_float), ("structure", C.c_float)]


lib.fluid_version.restype = C.c_uint32
lib.fluid_last_error.restype = C.c_char_p
lib.fluid_default_world_def.restype = WorldDef
lib.fluid_default_blob_def.restype = BlobDef
lib.fluid_box_shape.restype = Shape
lib.fluid_box_shape.argtypes = [Vec2, Vec2]
lib.fluid_world_step.argtypes = [C.c_void_p, C.c_float]
for name in ("fluid_world_def_set_quality", "fluid_world_create", "fluid_material_preset",
             "fluid_world_add_material", "fluid_world_add_plugin", "fluid_world_spawn_blob",
             "fluid_world_step", "fluid_world_positions"):
    getattr(lib, name).restype = C.c_int


def ok(status, what):
    if status != 0:
        sys.exit(f"ctypes_smoke: {what}: status {status}: {lib.fluid_last_error().decode()}")


if lib.fluid_version() // 100 != 1:
    sys.exit(f"ctypes_smoke: the library's C API is version {lib.fluid_version()}, not 1.x")

world_def = lib.fluid_default_world_def()
ok(lib.fluid_world_def_set_quality(C.byref(world_def), b"game"), "quality")
world = C.c_void_p()
ok(lib.fluid_world_create(C.byref(world_def), C.byref(world)), "create")
water = MaterialDef()
ok(lib.fluid_material_preset(b"water", C.byref(water)), "water")
material = MaterialId()
ok(lib.fluid_world_add_material(world, C.byref(water), C.byref(material)), "material")
plugin = PluginId()
tank = (Param * 4)(Param(b"minX", 0.0), Param(b"minY", 0.0), Param(b"maxX", 1.0),
                   Param(b"maxY", 2.0))
ok(lib.fluid_world_add_plugin(world, b"boundary.box", tank, 4, C.byref(plugin)), "tank")
gravity = (Param * 1)(Param(b"gy", -9.81))
ok(lib.fluid_world_add_plugin(world, b"force.gravity", gravity, 1, C.byref(plugin)), "gravity")
blob = lib.fluid_default_blob_def()
blob.shape = lib.fluid_box_shape(Vec2(0.0, 0.0), Vec2(0.4, 0.6))
blob.material = material
spawned = C.c_uint32()
ok(lib.fluid_world_spawn_blob(world, C.byref(blob), C.byref(spawned)), "blob")

for _ in range(60):
    ok(lib.fluid_world_step(world, 1.0 / 60.0), "step")
x, y = C.POINTER(C.c_float)(), C.POINTER(C.c_float)()
count = C.c_uint32()
ok(lib.fluid_world_positions(world, C.byref(x), C.byref(y), C.byref(count)), "positions")
n = count.value
xs = [x[i] for i in range(n)]
ys = [y[i] for i in range(n)]
mean_y = sum(ys) / n
print(f"ctypes_smoke: {n} particles of {spawned.value}, mean height {mean_y:.3f} m (0.3 m at "
      f"the start), furthest {max(xs):.3f} m (0.4 m)")
failed = []
if n != spawned.value:
    failed.append("particles were lost")
if not (mean_y < 0.25 and max(xs) > 0.6):
    failed.append("the dam did not break")
if not all(0.0 <= v <= 1.0 for v in xs) or not all(0.0 <= v <= 2.0 for v in ys):
    failed.append("particles left the tank")

status = lib.fluid_world_add_plugin(world, b"force.nope", None, 0, C.byref(plugin))
message = lib.fluid_last_error().decode()
print(f"ctypes_smoke: an unknown plugin: status {status}, '{message}'")
if status != 4 or "force.nope" not in message:
    failed.append("the unknown plugin's status or message")
lib.fluid_world_destroy(world)
if failed:
    sys.exit("ctypes_smoke: " + "; ".join(failed))
