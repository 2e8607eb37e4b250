// fluid — the checks every library runs on the values it is given (internal: shared by the
// core, fluid::level, fluid::box2d and fluid::gl; not installed).
#pragma once

#include <fluid/error.h>

#include <glm/vec2.hpp>

#include <cmath>
#include <sstream>
#include <string_view>
#include <type_traits>

namespace fluid::internal {

/// True when both coordinates are finite. Any thread.
inline bool finite(glm::vec2 v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
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
        s << prefix << field << " = " << value << " is out of range [" << lo << ", " << hi
          << "] (unit: " << unit << ")";
        throw Error(s.str());
    }
}

} // namespace fluid::internal
