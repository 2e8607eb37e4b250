// fluid::box2d — plain little-endian binary fields for the coupling's and Box2D's saves
// (internal).
#pragma once

#include <fluid/error.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>

namespace fluid::box2d::binary {

/// Writes plain values to `out` as their bytes (every supported machine is little-endian, like
/// the world's snapshots).
class Writer {
public:
    explicit Writer(std::ostream& out) : m_out(out) {}
    template <class T> void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        m_out.write(reinterpret_cast<const char*>(&value), sizeof(T));
    }

private:
    std::ostream& m_out;
};

/// Reads what `Writer` wrote; a short read throws `fluid::Error` "<what>: truncated (...)".
class Reader {
public:
    Reader(std::istream& in, std::string what) : m_in(in), m_what(std::move(what)) {}
    /// The next value; `field` names it in the error.
    template <class T> T get(const char* field) {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        if (!m_in.read(reinterpret_cast<char*>(&value), sizeof(T))) {
            fail(std::string("truncated (ended while reading ") + field + ")");
        }
        return value;
    }
    /// The next float or double, finite and within [lo, hi]; otherwise throws "<what>: <field> =
    /// <value> is not finite or out of [lo, hi] (unit: <unit>)" (without the unit when `unit` is
    /// null).
    template <class T>
    T number(const std::string& field, T lo, T hi, const char* unit = nullptr) {
        static_assert(std::is_floating_point_v<T>);
        const T v = get<T>(field.c_str());
        if (!std::isfinite(v) || v < lo || v > hi) {
            std::ostringstream s;
            s << field << " = " << v << " is not finite or out of [" << lo << ", " << hi << "]";
            if (unit != nullptr) {
                s << " (unit: " << unit << ")";
            }
            fail(s.str());
        }
        return v;
    }
    /// A count no larger than `limit`, nor than the stream's remaining bytes hold at
    /// `minBytesEach` bytes per entry (checked before anything is sized by it).
    uint32_t count(const char* field, uint32_t limit, uint32_t minBytesEach = 0) {
        const auto n = get<uint32_t>(field);
        if (n > limit) {
            fail(std::string(field) + " = " + std::to_string(n) + " is more than " +
                 std::to_string(limit) + " (corrupt)");
        }
        const uint64_t left = remaining();
        if (minBytesEach > 0 && uint64_t(n) * minBytesEach > left) {
            fail(std::string(field) + " = " + std::to_string(n) + " needs at least " +
                 std::to_string(uint64_t(n) * minBytesEach) + " bytes; " + std::to_string(left) +
                 " remain");
        }
        return n;
    }
    /// Bytes left in the stream (unit: bytes; the largest uint64_t when the stream cannot
    /// tell, e.g. a pipe).
    uint64_t remaining() {
        const std::istream::pos_type at = m_in.tellg();
        if (at == std::istream::pos_type(-1) || !m_in.seekg(0, std::ios::end)) {
            m_in.clear();
            return std::numeric_limits<uint64_t>::max();
        }
        const std::istream::pos_type end = m_in.tellg();
        m_in.seekg(at);
        return end >= at ? uint64_t(end - at) : 0;
    }
    /// Throws `fluid::Error` "<what>: <message>".
    [[noreturn]] void fail(const std::string& message) const {
        throw Error(m_what + ": " + message);
    }

private:
    std::istream& m_in;
    std::string m_what;
};

} // namespace fluid::box2d::binary
