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

/// Throws `fluid::Error` "<prefix><field> = <value> is out of range [<lo>, <hi>] (unit:
/// <unit>)" unless `value` lies in [lo, hi] (a NaN or an infinity never does). Any thread.
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
        throw Error(s.str());
    }
}

/// What is wrong with `name` as a name (of a material, a plugin, an emitter...): "" when it
/// is printable text, otherwise "the name holds a control character (byte 0x00 at offset 2);
/// names are printable text" for its first byte below 0x20 or equal to 0x7f (UTF-8 multibyte
/// characters are allowed). Pure function; any thread.
inline std::string nameProblem(std::string_view name) {
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

} // namespace fluid::internal
