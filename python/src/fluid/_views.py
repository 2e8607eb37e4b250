"""Zero-copy NumPy views of a world's particle arrays, refused once the world has changed.

The C API hands out pointers into the world's own storage (fluid_world_positions and the
others), valid "until the next call that changes the world". The core swaps each channel with a
scratch buffer when it sorts the particles (every sub-step) and reallocates them when particles
are added, so an old pointer then reads another array's data or freed memory. A NumPy array
cannot be revoked, so the arrays handed out are GuardedArray, an ndarray subclass that carries
the world's change counter (its generation) at the time it was made and checks it on every
access that reads the memory: indexing, iteration, ufuncs and NumPy functions, printing,
tolist/tobytes/copy. Copies own their memory and are never checked.
"""
import numpy as np

from .errors import ExpiredViewError

_EXPIRED = ("{what}: the world changed since this array was taken (a step, a spawn, a "
            "removal...), so its memory may have moved or been freed; ask the world again "
            "(world.particles) or copy the array (numpy.array(a)) before changing the world")


class Generation:
    """A change counter: arrays made at one value are refused at any other. Any thread that
    owns the world (the world's thread rule)."""

    __slots__ = ("value", "__weakref__")

    def __init__(self):
        self.value = 0

    def bump(self):
        """Invalidates every array handed out so far."""
        self.value += 1


def _checked(a):
    """Raises ExpiredViewError when `a` (or the view it derives from) has expired."""
    guard = a._fluid_guard
    if guard is None or guard[0].value == guard[1]:
        return
    # Copies (and arrays derived from a copy) own their memory: fine forever.
    b = a
    while isinstance(b, np.ndarray):
        if b.flags.owndata:
            return
        b = b.base
    raise ExpiredViewError(_EXPIRED.format(what=guard[2]))


def _plain(x):
    if isinstance(x, GuardedArray):
        _checked(x)
        return x.view(np.ndarray)
    return x


class GuardedArray(np.ndarray):
    """A NumPy array viewing a world's memory (no copy), valid until the world changes.

    Read-only for the world's data (positions, velocities...), writable only where the C API
    lets the caller write (a force plugin's accelerations, its own range). Every read checks
    that the world has not changed since the array was made and raises ExpiredViewError
    otherwise. ``numpy.array(a)`` / ``a.copy()`` make a copy that stays valid;
    ``numpy.asarray(a)`` and ``memoryview(a)`` strip the check (the same lifetime rule, no
    guard): use them only inside the frame. Thread rule: the world's.
    """

    _fluid_guard = None

    def __array_finalize__(self, obj):
        self._fluid_guard = getattr(obj, "_fluid_guard", None)

    def __getitem__(self, key):
        _checked(self)
        return super().__getitem__(key)

    def __setitem__(self, key, value):
        _checked(self)
        super().__setitem__(key, _plain(value))

    def __iter__(self):
        _checked(self)
        return super().__iter__()

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        inputs = tuple(_plain(x) for x in inputs)
        out = kwargs.get("out")
        if out:
            kwargs["out"] = tuple(_plain(o) for o in out)
        result = getattr(ufunc, method)(*inputs, **kwargs)
        if out:
            return out[0] if len(out) == 1 else out
        return result

    def __array_function__(self, func, types, args, kwargs):
        _checked(self)
        args = tuple(_plain(a) for a in args)
        kwargs = {k: _plain(v) for k, v in kwargs.items()}
        return func(*args, **kwargs)

    def __repr__(self):
        _checked(self)
        return "GuardedArray(" + repr(self.view(np.ndarray)) + ")"

    def __str__(self):
        _checked(self)
        return str(self.view(np.ndarray))

    def __reduce__(self):
        _checked(self)
        return self.view(np.ndarray).copy().__reduce__()

    def __float__(self):
        _checked(self)
        return super().__float__()

    def __int__(self):
        _checked(self)
        return super().__int__()

    def __bool__(self):
        _checked(self)
        return super().__bool__()

    def tolist(self):
        """As ndarray.tolist, after the check."""
        _checked(self)
        return super().tolist()

    def tobytes(self, order="C"):
        """As ndarray.tobytes, after the check."""
        _checked(self)
        return super().tobytes(order)

    def copy(self, order="C"):
        """A copy (a plain ndarray that owns its memory and stays valid), after the check."""
        _checked(self)
        return np.array(self.view(np.ndarray), order=order, copy=True)

    def __copy__(self):
        return self.copy()

    def __deepcopy__(self, memo):
        return self.copy()


def guarded(ffi, pointer, count, dtype, generation, what, writable=False):
    """A GuardedArray of `count` items of `dtype` at the C pointer `pointer` (no copy)."""
    dtype = np.dtype(dtype)
    if count == 0 or pointer == ffi.NULL:
        a = np.empty(0, dtype=dtype).view(GuardedArray)
    else:
        a = np.frombuffer(ffi.buffer(pointer, count * dtype.itemsize), dtype=dtype)
        a = a.view(GuardedArray)
    a._fluid_guard = (generation, generation.value, what)
    if not writable:
        a.flags.writeable = False
    return a
