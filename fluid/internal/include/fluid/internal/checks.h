// fluid — the checks every library runs on the values it is given (internal: shared by the
// core, fluid::level, fluid::box2d and fluid::gl; not installed).
#pragma once

#include <fluid/error.h>

#include <glm/vec2.hpp>

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>

namespace fluid::internal {

/// True when both coordinates are finite. Any thread.
inline bool finite(glm::vec2 v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

/// `value` as messages print it: as a stream prints it (6 significant digits), with more digits
/// when those 6 would read back as another number, so that a value just outside a bound never
/// prints as the bound itself ("9.999999e-05", not "0.0001", just below a minimum of 1e-4). Any
/// thread.
template <class T> std::string formatValue(T value) {
    std::ostringstream s;
    if constexpr (std::is_floating_point_v<T>) {
        for (int digits = 6; digits <= std::numeric_limits<T>::max_digits10; ++digits) {
            s.str("");
            s.precision(digits);
            s << value;
            const std::string text = s.str();
            const auto back = static_cast<T>(std::strtold(text.c_str(), nullptr));
            if (back == value || !std::isfinite(value)) {
                break;
            }
        }
    } else {
        s << value;
    }
    return s.str();
}

/// Throws `fluid::Error` (`ErrorCode::OutOfRange`) "<prefix><field> = <value> is out of range
/// [<lo>, <hi>] (unit: <unit>)" unless `value` lies in [lo, hi] (a NaN or an infinity never does).
/// Any thread.
template <class T>
void checkRange(std::string_view prefix, std::string_view field, T value, T lo, T hi,
                std::string_view unit) {
    bool inside = value >= lo && value <= hi;
    if constexpr (std::is_floating_point_v<T>) {
        inside = inside && std::isfinite(value);
    }
    if (!inside) {
        std::ostringstream s;
        s << prefix << field << " = " << formatValue(value) << " is out of range [" << lo << ", "
          << hi << "] (unit: " << unit << ")";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
}

/// `text` as an error message quotes it: between apostrophes, control characters written as
/// `Error::printable` writes them, and at most `kMaxNameBytes` bytes of it, cut before a UTF-8
/// character that would not fit, with the whole length after a cut one: "'abc'",
/// "'abcd...' (1048576 bytes)". Every message that quotes a caller's string quotes it through
/// this function. Pure function; any thread.
inline std::string quoted(std::string_view text) {
    std::size_t cut = text.size();
    if (cut > kMaxNameBytes) {
        cut = kMaxNameBytes;
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) {
            --cut; // text[cut] continues a multibyte character: cut before the character
        }
    }
    std::string out(1, '\'');
    out.append(Error::printable(text.substr(0, cut)));
    if (cut == text.size()) {
        out.push_back('\'');
    } else {
        out.append("...' (").append(std::to_string(text.size())).append(" bytes)");
    }
    return out;
}

/// What is wrong with `name` as a name (of a material, a plugin type or parameter, a level's
/// objects): "" when it is printable text of at most `kMaxNameBytes` bytes, otherwise "the name
/// is 300 bytes long; names are at most 256 bytes", or "the name holds a control character
/// (byte 0x00 at offset 2); names are printable text" for its first byte below 0x20 or equal
/// to 0x7f (UTF-8 multibyte characters are allowed). The one rule for names: every name the
/// libraries take is checked here. Pure function; any thread.
inline std::string nameProblem(std::string_view name) {
    if (name.size() > kMaxNameBytes) {
        return "the name is " + std::to_string(name.size()) + " bytes long; names are at most " +
               std::to_string(kMaxNameBytes) + " bytes";
    }
    for (std::size_t k = 0; k < name.size(); ++k) {
        const auto byte = static_cast<unsigned char>(name[k]);
        if (byte < 0x20 || byte == 0x7f) {
            constexpr char kHex[] = "0123456789abcdef";
            return std::string("the name holds a control character (byte 0x") + kHex[byte >> 4] +
                   kHex[byte & 0xf] + " at offset " + std::to_string(k) +
                   "); names are printable text";
        }
    }
    return {};
}

/// Throws `fluid::Error` (`ErrorCode::BadArgument`) "<what> '<name>': <problem>" (the name
/// `quoted`, the problem `nameProblem`'s) unless `name` is a good name, e.g. "Registry::add: plugin
/// type 'a\x07': the name holds a control character (byte 0x07 at offset 1); names are printable
/// text". Any thread.
inline void checkName(std::string_view what, std::string_view name) {
    if (const std::string problem = nameProblem(name); !problem.empty()) {
        throw Error(std::string(what) + " " + quoted(name) + ": " + problem,
                    ErrorCode::BadArgument);
    }
}

} // namespace fluid::internal
