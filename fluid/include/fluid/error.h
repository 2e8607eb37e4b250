// fluid — 2D SPH liquid for games.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fluid {

/// What kind of failure a `fluid::Error` reports, for a program to branch on without reading
/// the message.
enum class ErrorCode : uint8_t {
    /// Bad input: a value out of range or not finite, a stale handle, an unknown name, a full
    /// world, a bad file (the message says which).
    BadInput = 0,
    /// A call the world refuses in its present state, whatever its arguments: a change to a
    /// world made from inside its own `World::step` (a plugin's hook calling back into the world
    /// that runs it).
    WrongState = 1,
};

/// The longest name fluid takes (unit: bytes of UTF-8; a name is printable text of 0 to 256
/// bytes): a material's, a plugin type's, a declared parameter's, a level file's objects'.
/// Longer names are refused ("the name is 300 bytes long; names are at most 256 bytes"), and an
/// error message quotes at most this many bytes of any string it was given ("plugin type
/// 'force.xxx...' (1048576 bytes)"), so a message stays short whatever the caller passed.
/// Compile-time constant; any thread.
inline constexpr std::size_t kMaxNameBytes = 256;

/// The one exception type fluid throws for bad input (non-finite or out-of-range values, stale
/// handles, a full world, unknown plugin types) and for calls the world's state refuses. The
/// message names the function, the value and what was expected. Thread rule: thrown only on the
/// thread that called into fluid; a throwing call leaves the world unchanged.
class Error : public std::runtime_error {
public:
    /// Wraps `message` (UTF-8, one line). Control characters in it (bytes below 0x20 and
    /// 0x7f: a NUL, a line break or an escape sequence quoted from a user's string) are written
    /// as `printable` writes them, so `what()` is never cut short at a NUL and cannot drive a
    /// terminal.
    explicit Error(const std::string& message, ErrorCode code = ErrorCode::BadInput)
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
    ErrorCode m_code = ErrorCode::BadInput;
};

} // namespace fluid
