// fluid — 2D SPH liquid for games.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fluid {

/// What kind of failure a `fluid::Error` reports, for a program to branch on without reading
/// the message. The numeric values are stable (new kinds are added at the end); the C API maps
/// each to a `fluid_status` (docs/errors.md).
enum class ErrorCode : uint8_t {
    /// A malformed argument: a value not finite, negative or zero where it must be positive, a
    /// bad shape or name, a null plugin or an empty visitor, values inconsistent with each other
    /// (C: FLUID_ERROR_INVALID_ARGUMENT).
    BadArgument = 0,
    /// A call the world refuses in its present state, whatever its arguments: a change to a
    /// world made from inside its own `World::step` (a plugin's hook calling back into the world
    /// that runs it), a world stepped by the wrong host (C: FLUID_ERROR_REFUSED).
    WrongState = 1,
    /// A number outside its documented range: a setting, a parameter, an index past a list's end
    /// (C: FLUID_ERROR_INVALID_ARGUMENT).
    OutOfRange = 2,
    /// An id or particle handle that no longer names anything in this world: removed, never made
    /// by it, made by another world, or null (C: FLUID_ERROR_STALE_ID).
    StaleId = 3,
    /// A name nothing is registered under: a plugin type or parameter, a material, a preset, a
    /// quality, a key's value (C: FLUID_ERROR_UNKNOWN_NAME).
    UnknownName = 4,
    /// A limit reached: the world's maxParticles, 65535 materials, every world tag used
    /// (C: FLUID_ERROR_LIMIT).
    Full = 5,
    /// Malformed contents of a level file, a level save or a snapshot: bad JSON, a corrupt or
    /// truncated snapshot, a value the file may not hold (C: FLUID_ERROR_BAD_FILE).
    BadFile = 6,
    /// A file or stream that cannot be opened, read or written (C: FLUID_ERROR_IO).
    Io = 7,
    /// Memory ran out; the `std::bad_alloc` rides along as the nested exception where fluid
    /// caught one (C: FLUID_ERROR_OUT_OF_MEMORY).
    OutOfMemory = 8,
};

/// A name and the value it stands for: one row of an enum's name table (`kErrorCodeNames`,
/// `kQualityNames`...), the one place that enum's names are written.
template <class Enum> struct EnumName {
    /// The value.
    Enum value;
    /// Its name (lower-case ASCII, as level files, command lines and messages write it).
    std::string_view name;
};

/// The name of `value` in `table`, "" for a value not listed. Pure function; any thread.
template <class Enum, std::size_t N>
constexpr std::string_view nameIn(const EnumName<Enum> (&table)[N], Enum value) {
    for (const EnumName<Enum>& row : table) {
        if (row.value == value) {
            return row.name;
        }
    }
    return {};
}

/// The value named `name` in `table` (exact, case-sensitive match), nothing for a name not
/// listed. Pure function; any thread.
template <class Enum, std::size_t N>
constexpr std::optional<Enum> valueIn(const EnumName<Enum> (&table)[N], std::string_view name) {
    for (const EnumName<Enum>& row : table) {
        if (row.name == name) {
            return row.value;
        }
    }
    return std::nullopt;
}

/// The names in `table` in its order, for a message listing the valid ones: "a, b or c" with
/// `last` = " or ", "a, b, c" with `last` = ", ". Pure function; any thread.
template <class Enum, std::size_t N>
std::string namesIn(const EnumName<Enum> (&table)[N], std::string_view last = " or ") {
    std::string out;
    for (std::size_t k = 0; k < N; ++k) {
        if (k > 0) {
            out += k + 1 == N ? last : std::string_view(", ");
        }
        out += table[k].name;
    }
    return out;
}

/// The error codes' names, in numeric order: the one table of them.
inline constexpr EnumName<ErrorCode> kErrorCodeNames[] = {
    {ErrorCode::BadArgument, "bad argument"},  {ErrorCode::WrongState, "wrong state"},
    {ErrorCode::OutOfRange, "out of range"},   {ErrorCode::StaleId, "stale id"},
    {ErrorCode::UnknownName, "unknown name"},  {ErrorCode::Full, "full"},
    {ErrorCode::BadFile, "bad file"},          {ErrorCode::Io, "i/o"},
    {ErrorCode::OutOfMemory, "out of memory"},
};

/// The stable lower-case name of `code` ("bad argument", "stale id", "out of memory"), for
/// messages, logs and tests; "" for a value not listed. Pure function; any thread.
constexpr std::string_view errorCodeName(ErrorCode code) {
    return nameIn(kErrorCodeNames, code);
}

/// The code named `name` (as `errorCodeName` writes it), nothing for an unknown name. Pure
/// function; any thread.
constexpr std::optional<ErrorCode> errorCodeFromName(std::string_view name) {
    return valueIn(kErrorCodeNames, name);
}

/// The longest name fluid takes (unit: bytes of UTF-8; a name is printable text of 0 to 256
/// bytes): a material's, a plugin type's, a declared parameter's, a level file's objects'.
/// Longer names are refused ("the name is 300 bytes long; names are at most 256 bytes"), and an
/// error message quotes at most this many bytes of any string it was given ("plugin type
/// 'force.xxx...' (1048576 bytes)"), so a message stays short whatever the caller passed.
/// Compile-time constant; any thread.
inline constexpr std::size_t kMaxNameBytes = 256;

/// The one exception type fluid throws for bad input (non-finite or out-of-range values, stale
/// handles, a full world, unknown plugin types, bad files) and for calls the world's state
/// refuses. The message names the function, the value and what was expected; `code()` says
/// which kind of failure it is. Thread rule: thrown only on the
/// thread that called into fluid; a throwing call leaves the world unchanged.
class Error : public std::runtime_error {
public:
    /// Wraps `message` (UTF-8, one line). Control characters in it (bytes below 0x20 and
    /// 0x7f: a NUL, a line break or an escape sequence quoted from a user's string) are written
    /// as `printable` writes them, so `what()` is never cut short at a NUL and cannot drive a
    /// terminal. `code` is the kind of failure (`ErrorCode`).
    explicit Error(const std::string& message, ErrorCode code = ErrorCode::BadArgument)
        : std::runtime_error(printable(message)), m_code(code) {}

    /// The kind of failure. Any thread.
    ErrorCode code() const noexcept { return m_code; }

    /// `text` with every control character (a byte below 0x20, or 0x7f) written as "\xNN" (two
    /// lower-case hex digits); every other byte, UTF-8 multibyte characters included, stays as
    /// it is. Pure function; any thread.
    static std::string printable(std::string_view text) {
        std::string out;
        out.reserve(text.size());
        for (const char c : text) {
            const auto byte = static_cast<unsigned char>(c);
            if (byte < 0x20 || byte == 0x7f) {
                constexpr char kHex[] = "0123456789abcdef";
                out += "\\x";
                out += kHex[byte >> 4];
                out += kHex[byte & 0xf];
            } else {
                out += c;
            }
        }
        return out;
    }

private:
    ErrorCode m_code = ErrorCode::BadArgument;
};

} // namespace fluid
