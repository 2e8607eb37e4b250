// fluid — 2D SPH liquid for games.
#pragma once

#include <stdexcept>
#include <string>

namespace fluid {

/// The one exception type fluid throws for bad input (non-finite or out-of-range values, stale
/// handles, a full world, unknown plugin types). The message names the function, the value and
/// what was expected. Thread rule: thrown only on the thread that called into fluid; a throwing
/// call leaves the world unchanged.
class Error : public std::runtime_error {
public:
    /// Wraps `message` (UTF-8, one line).
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

} // namespace fluid
