// fluid::box2d — plain little-endian binary fields for the coupling's and Box2D's saves
// (internal).
#pragma once

#include <fluid/error.h>

#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
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
    /// A count no larger than `limit`.
    uint32_t count(const char* field, uint32_t limit) {
        const auto n = get<uint32_t>(field);
        if (n > limit) {
            fail(std::string(field) + " = " + std::to_string(n) + " is more than " +
                 std::to_string(limit) + " (corrupt)");
        }
        return n;
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
