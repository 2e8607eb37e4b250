// fluid — 2D SPH liquid for games.
#pragma once

#include <cstdint>
#include <string_view>

namespace fluid {

/// One number of a definition struct `Def` (a `float` or a `uint32_t` member) as validation,
/// level files, snapshots, the demo's tuning panel and docs/levels.md read it: `materialFields()`,
/// `worldFields()`, `positionBasedFields()` and `emitterFields()` list each number once. Exactly
/// one of `real` and `whole` is set. Plain data.
template <class Def> struct Field {
    /// Key in level files and name in error messages (e.g. "yieldStress").
    std::string_view name;
    /// The member when the number is a float.
    float Def::*real = nullptr;
    /// The member when the number is a whole count.
    uint32_t Def::*whole = nullptr;
    /// SI unit (e.g. "Pa"; "1" for dimensionless, "count").
    std::string_view unit;
    /// Smallest accepted value (unit: `unit`; refused itself when `openLow`).
    double lo = 0.0;
    /// Largest accepted value (unit: `unit`).
    double hi = 0.0;
    /// True when `lo` itself is refused (a range (lo, hi]).
    bool openLow = false;
    /// One line for humans (docs/levels.md's tables, the demo's tooltips).
    std::string_view description;

    /// The member's value in `def` (unit: `unit`).
    double get(const Def& def) const {
        return real != nullptr ? double(def.*real) : double(def.*whole);
    }
    /// Sets the member in `def` to `value` (unit: `unit`; rounded to the member's type).
    void set(Def& def, double value) const {
        if (real != nullptr) {
            def.*real = float(value);
        } else {
            def.*whole = uint32_t(value);
        }
    }
};

} // namespace fluid
