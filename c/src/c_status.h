// fluid::c — the C status each C++ error code maps to: the one table of it (docs/errors.md).
#pragma once
#include <fluid/c.h>

#include <fluid/error.h>

namespace fluid::c {

/// The status a `fluid::Error` with `code` becomes at the C API (docs/errors.md): bad
/// arguments and values out of range are FLUID_ERROR_INVALID_ARGUMENT, every other kind has a
/// status of its own. FLUID_ERROR_NULL_ARGUMENT has no code: the C layer reports it itself.
/// Pure function; any thread.
constexpr fluid_status statusOf(ErrorCode code) noexcept {
    switch (code) {
    case ErrorCode::BadArgument:
    case ErrorCode::OutOfRange:
        return FLUID_ERROR_INVALID_ARGUMENT;
    case ErrorCode::WrongState:
        return FLUID_ERROR_REFUSED;
    case ErrorCode::StaleId:
        return FLUID_ERROR_STALE_ID;
    case ErrorCode::UnknownName:
        return FLUID_ERROR_UNKNOWN_NAME;
    case ErrorCode::Full:
        return FLUID_ERROR_LIMIT;
    case ErrorCode::BadFile:
        return FLUID_ERROR_BAD_FILE;
    case ErrorCode::Io:
        return FLUID_ERROR_IO;
    case ErrorCode::OutOfMemory:
        return FLUID_ERROR_OUT_OF_MEMORY;
    }
    return FLUID_ERROR_INVALID_ARGUMENT; // a value not listed: not made by fluid
}

} // namespace fluid::c
