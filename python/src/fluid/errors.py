"""fluid's exceptions: one class per fluid_status of the C API (fluid/c.h, docs/errors.md).

Every failing call raises the class of its status; ``str(error)`` is the C API's message
(fluid_last_error(), the C++ library's text), ``error.status`` the fluid_status number and
``error.status_name`` its name ("FLUID_ERROR_STALE_ID"). Each class also derives from the
closest built-in exception (ValueError, LookupError, OSError...), so ``except ValueError``
catches a bad argument too.
"""
from ._fluid_c import ffi, lib


#: The class raised for each fluid_status (filled by FluidError's subclasses below).
BY_STATUS = {}


class FluidError(Exception):
    """A call of the C API that did not return FLUID_OK.

    Attributes: ``status`` (int, the fluid_status), ``status_name`` (str), ``message`` (str,
    the C API's message, also ``str(error)``). Any thread.
    """

    status = -1
    status_name = "unknown status"

    def __init_subclass__(cls, status=None, **kwargs):
        """``class X(FluidError, status=lib.FLUID_ERROR_...)`` gives X that status and the C
        API's own name for it (fluid_status_name), and makes X the class raised for it."""
        super().__init_subclass__(**kwargs)
        if status is not None:
            cls.status = status
            cls.status_name = ffi.string(lib.fluid_status_name(status)).decode()
            BY_STATUS[status] = cls

    def __init__(self, message, status=None, status_name=None):
        super().__init__(message)
        self.message = message
        if status is not None:
            self.status = status
        if status_name is not None:
            self.status_name = status_name

    def __str__(self):
        return self.message


class InvalidArgumentError(FluidError, ValueError, status=lib.FLUID_ERROR_INVALID_ARGUMENT):
    """FLUID_ERROR_INVALID_ARGUMENT (1): a value out of its range, NaN or inconsistent."""


class NullArgumentError(FluidError, ValueError, status=lib.FLUID_ERROR_NULL_ARGUMENT):
    """FLUID_ERROR_NULL_ARGUMENT (2): a required pointer was NULL (a bug of this package)."""


class StaleIdError(FluidError, LookupError, status=lib.FLUID_ERROR_STALE_ID):
    """FLUID_ERROR_STALE_ID (3): an id or particle that no longer exists, or another world's."""


class UnknownNameError(FluidError, LookupError, status=lib.FLUID_ERROR_UNKNOWN_NAME):
    """FLUID_ERROR_UNKNOWN_NAME (4): a preset, plugin type, field or parameter name."""


class BadFileError(FluidError, ValueError, status=lib.FLUID_ERROR_BAD_FILE):
    """FLUID_ERROR_BAD_FILE (5): a level file, save or snapshot that cannot be read."""


class FileIOError(FluidError, OSError, status=lib.FLUID_ERROR_IO):
    """FLUID_ERROR_IO (6): a file that cannot be opened or written."""


class LimitError(FluidError, status=lib.FLUID_ERROR_LIMIT):
    """FLUID_ERROR_LIMIT (7): the world's max_particles, 65535 materials."""


class OutOfMemoryError(FluidError, MemoryError, status=lib.FLUID_ERROR_OUT_OF_MEMORY):
    """FLUID_ERROR_OUT_OF_MEMORY (8): memory ran out."""


class RefusedError(FluidError, RuntimeError, status=lib.FLUID_ERROR_REFUSED):
    """FLUID_ERROR_REFUSED (9): the world refused a call in its state (inside its own step)."""


class PluginError(FluidError, RuntimeError):
    """A force plugin written in Python raised during a step. The step itself finished (the C
    API has no way to stop it from a callback); that plugin added nothing from then on in that
    step. The plugin's exception is ``__cause__``. Not a C status (``status`` is -1)."""

    status, status_name = -1, "python plugin"


class ExpiredViewError(RuntimeError):
    """An array of particle data read after the world changed (a step, a spawn, a removal...):
    its memory may have been moved or freed. Ask the world again (``world.particles``) or copy
    the array (``numpy.array(a)``) before changing the world."""


class ClosedError(RuntimeError):
    """A world or level used after close() (or a level's world after the level closed)."""
