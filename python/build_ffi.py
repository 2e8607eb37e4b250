"""The cffi builder of fluid's Python package (API mode, out of line).

The declarations are fluid/c.h's own, read from the header (preprocessor lines and the export
macro taken out), and the generated C source includes <fluid/c.h>: the C compiler checks every
struct, field and function against the real header, so a layout that drifts fails the build
instead of reading the wrong bytes.

Where the library is, in this order (the first that names a directory wins):

  FLUID_BUILD_DIR=/path/to/build/release   a CMake build tree of the project: its
                                           c/libfluid_c.so and the source's c/include
                                           (read from the tree's CMakeCache.txt, or
                                           FLUID_SOURCE_DIR)
  FLUID_PREFIX=/usr/local                  an installed prefix: PREFIX/include, PREFIX/lib*
  pkg-config fluid-c                       the installed fluid-c.pc (--cflags --libs)
  ../build/release                         next to this file, when the package sits in the
                                           project's source tree

The extension links libfluid_c.so with an rpath to its directory, so it loads without
LD_LIBRARY_PATH (rebuild the package when the library moves).
"""
import os
import re
import shlex
import subprocess
import sys

from cffi import FFI

HERE = os.path.dirname(os.path.abspath(__file__))


def _fail(message):
    sys.exit("fluid (python): " + message)


def _source_dir_of(build_dir):
    explicit = os.environ.get("FLUID_SOURCE_DIR")
    if explicit:
        return explicit
    cache = os.path.join(build_dir, "CMakeCache.txt")
    if os.path.isfile(cache):
        with open(cache, encoding="utf-8") as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    return line.split("=", 1)[1].strip()
    return os.path.dirname(HERE)


def _lib_dir_in(prefix):
    for sub in ("lib", "lib64", os.path.join("lib", "x86_64-linux-gnu"),
                os.path.join("lib", "aarch64-linux-gnu")):
        candidate = os.path.join(prefix, sub)
        if os.path.exists(os.path.join(candidate, "libfluid_c.so")):
            return candidate
    return None


def locate():
    """(include_dirs, library_dirs, where) of fluid/c.h and libfluid_c.so."""
    build_dir = os.environ.get("FLUID_BUILD_DIR")
    if build_dir:
        build_dir = os.path.abspath(build_dir)
        lib_dir = os.path.join(build_dir, "c")
        if not os.path.exists(os.path.join(lib_dir, "libfluid_c.so")):
            _fail(f"FLUID_BUILD_DIR={build_dir}: no c/libfluid_c.so there (build the target "
                  "fluid_c_shared first)")
        include = os.path.join(_source_dir_of(build_dir), "c", "include")
        return [include], [lib_dir], f"build tree {build_dir}"
    prefix = os.environ.get("FLUID_PREFIX")
    if prefix:
        lib_dir = _lib_dir_in(prefix)
        if lib_dir is None:
            _fail(f"FLUID_PREFIX={prefix}: no libfluid_c.so in its lib directories")
        return [os.path.join(prefix, "include")], [lib_dir], f"prefix {prefix}"
    try:
        flags = subprocess.run(["pkg-config", "--cflags", "--libs", "fluid-c"],
                               capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        flags = None
    if flags:
        words = shlex.split(flags)
        includes = [w[2:] for w in words if w.startswith("-I")]
        libs = [w[2:] for w in words if w.startswith("-L")]
        return includes, libs, "pkg-config fluid-c"
    in_tree = os.path.join(os.path.dirname(HERE), "build", "release")
    if os.path.exists(os.path.join(in_tree, "c", "libfluid_c.so")):
        return [os.path.join(os.path.dirname(HERE), "c", "include")], \
            [os.path.join(in_tree, "c")], f"build tree {in_tree}"
    _fail("cannot find libfluid_c.so: set FLUID_BUILD_DIR to the project's build directory "
          "(e.g. build/release) or FLUID_PREFIX to where it is installed, or install fluid-c.pc "
          "for pkg-config")


def header_path(include_dirs):
    for d in include_dirs + ["/usr/include", "/usr/local/include"]:
        path = os.path.join(d, "fluid", "c.h")
        if os.path.isfile(path):
            return path
    _fail(f"no fluid/c.h under {include_dirs}")


def cdef_of(header_text):
    """fluid/c.h's declarations as cffi's cdef takes them."""
    lines = []
    for line in header_text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#"):
            continue  # include guard, export macro, includes, version macros (added below)
        if stripped.startswith('extern "C"') or stripped.startswith('} /* extern "C" */'):
            continue
        lines.append(line.replace("FLUID_C_API ", ""))
    text = "\n".join(lines)
    # cffi's parser knows no `/// ...` doc lines inside enums any better than C comments; both
    # are stripped by cffi itself. Keep the version constants from the header's values.
    return text + "\n#define FLUID_C_VERSION_MAJOR ...\n#define FLUID_C_VERSION_MINOR ...\n"


# The callbacks the package's Python force plugins use (fluid/_plugins.py).
PYTHON_CALLBACKS = """
extern "Python" void _fluid_py_force_prepare(void*, const fluid_step_context*);
extern "Python" void _fluid_py_force_apply(void*, const fluid_force_context*, uint32_t,
                                           uint32_t);
extern "Python" void _fluid_py_force_destroy(void*);
"""


def make_builder():
    include_dirs, library_dirs, where = locate()
    header = header_path(include_dirs)
    with open(header, encoding="utf-8") as f:
        declarations = cdef_of(f.read())
    if re.search(r"\bFLUID_C_API\b", declarations):
        _fail(f"{header}: an export macro left in the declarations")
    builder = FFI()
    builder.cdef(declarations + PYTHON_CALLBACKS)
    builder.set_source(
        "fluid._fluid_c",
        "#include <fluid/c.h>\n",
        include_dirs=include_dirs,
        library_dirs=library_dirs,
        libraries=["fluid_c"],
        extra_link_args=[f"-Wl,-rpath,{d}" for d in library_dirs],
        extra_compile_args=["-std=c99"])
    print(f"fluid (python): building against {where} ({header})", file=sys.stderr)
    return builder


ffibuilder = make_builder() if os.environ.get("FLUID_FFI_NO_BUILDER") is None else None

if __name__ == "__main__":
    ffibuilder.compile(verbose=True)
