// fluid — numbers in messages and level files, written as people write them (internal: shared
// by fluid::level and fluid::box2d; not installed).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace fluid::internal {

// The shortest text that reads back as `value`, as std::to_chars's general format writes it:
// the least digits that read back, fixed notation for decimal exponents -4 to 5, else
// scientific. std::to_chars where the standard library has it for floating point; else the
// same text from printf (emscripten's libc++ lacks the floating-point std::to_chars; how the two
// were compared: docs/web.md, "Number text").
template <class T> std::string shortestNumber(T value) {
#if defined(__cpp_lib_to_chars)
    char buffer[64];
    const auto result =
        std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general);
    return std::string(buffer, result.ptr);
#else
    char buffer[64];
    if (!std::isfinite(value)) {
        std::snprintf(buffer, sizeof(buffer), "%g", double(value));
        return buffer;
    }
    int digits = 1;
    for (; digits < 17; ++digits) {
        std::snprintf(buffer, sizeof(buffer), "%.*e", digits - 1, double(value));
        if (T(std::strtod(buffer, nullptr)) == value) {
            break;
        }
    }
    std::snprintf(buffer, sizeof(buffer), "%.*e", digits - 1, double(value));
    const int exponent = std::atoi(std::strchr(buffer, 'e') + 1);
    if (exponent >= -4 && exponent < 6) {
        std::snprintf(buffer, sizeof(buffer), "%.*f", std::max(digits - 1 - exponent, 0),
                      double(value));
    }
    return buffer;
#endif
}

/// A number as people write it: the shortest text that reads back as `value` (0.1, 1e+300,
/// 67108864). Pure function; any thread.
inline std::string formatNumber(double value) {
    // Whole numbers in full (100000, not 1e+05) up to 2^53, the largest seed (every whole
    // double up to there is exact); others in the shortest text that reads back.
    if (std::isfinite(value) && value == std::floor(value) &&
        std::fabs(value) <= 9007199254740992.0) {
        return std::to_string(int64_t(value));
    }
    return shortestNumber(value);
}

/// As above for a float (0.1f reads "0.1", not its double expansion). Pure function; any
/// thread.
inline std::string formatNumber(float value) {
    if (std::isfinite(value) && value == std::floor(value) && std::fabs(value) < 1e15f) {
        return std::to_string(int64_t(value));
    }
    return shortestNumber(value);
}

} // namespace fluid::internal
