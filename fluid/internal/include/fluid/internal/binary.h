// fluid — plain little-endian binary fields for every save the libraries write: the world's
// snapshots, level saves, Box2D worlds and the coupling's state (internal: shared by the core,
// fluid::level and fluid::box2d; not installed).
#pragma once

#include <fluid/error.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <istream>
#include <limits>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fluid::internal {

/// FNV-1a 64 of `bytes`: the checksum that closes snapshots and level saves. Any thread.
inline uint64_t fnv1a(std::span<const std::byte> bytes) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const std::byte b : bytes) {
        h ^= uint64_t(b);
        h *= 0x100000001b3ull;
    }
    return h;
}

/// `fnv1a` of a string's bytes. Any thread.
inline uint64_t fnv1a(std::string_view bytes) {
    return fnv1a(std::as_bytes(std::span<const char>(bytes.data(), bytes.size())));
}

/// Appends plain values to a byte string in memory (every supported machine is little-endian).
/// One thread at a time.
class ByteWriter {
public:
    /// A value as its bytes.
    template <class T> void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    /// A u64 count, then the entries.
    template <class T> void array(const std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        put<uint64_t>(values.size());
        bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    }
    /// A u64 length, then the bytes.
    void string(std::string_view text) {
        put<uint64_t>(text.size());
        bytes.append(text);
    }
    /// What was written.
    std::string bytes;
};

/// Reads what `ByteWriter` wrote from memory, without copying what it hands out as views.
/// Every error throws `fluid::Error` (`ErrorCode::BadFile`) "<what>: <message>", naming the field.
/// One thread at a time; the bytes outlive the reader.
class ByteReader {
public:
    /// Reads `bytes`; `what` opens every error ("snapshot: corrupt", "level save 'a.sav'").
    ByteReader(std::string_view bytes, std::string what) : m_data(bytes), m_what(std::move(what)) {}
    /// The next value; `field` names it in the error.
    template <class T> T get(const char* field = "a value") {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        std::memcpy(&value, take(sizeof(T), field).data(), sizeof(T));
        return value;
    }
    /// A u64 count, then that many entries into `values` (the count checked against the bytes
    /// left before `values` is sized by it).
    template <class T> void array(std::vector<T>& values, const char* field) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto n = get<uint64_t>(field);
        if (n > remaining() / sizeof(T)) {
            fail(std::string(field) + " claims " + std::to_string(n) + " entries, more than the " +
                 std::to_string(remaining()) + " bytes left hold");
        }
        values.resize(std::size_t(n));
        if (n > 0) { // memcpy into an empty vector's null data() is undefined
            std::memcpy(values.data(), take(std::size_t(n) * sizeof(T), field).data(),
                        std::size_t(n) * sizeof(T));
        }
    }
    /// A u64 length, then that many bytes, as a view into the reader's bytes.
    std::string_view bytes(const char* field) {
        const auto n = get<uint64_t>(field);
        if (n > remaining()) {
            fail(std::string(field) + " promises " + std::to_string(n) + " bytes; " +
                 std::to_string(remaining()) + " remain");
        }
        return take(std::size_t(n), field);
    }
    /// `bytes` as a string.
    std::string string(const char* field) { return std::string(bytes(field)); }
    /// An enum or bool stored as one byte, checked against its largest value (a byte that is
    /// not a valid value must never be loaded into the type).
    template <class E> E small(E largest, const char* field) {
        const auto raw = get<uint8_t>(field);
        if (raw > uint8_t(largest)) {
            fail(std::string(field) + " = " + std::to_string(raw) + " is not a valid value");
        }
        return E(raw);
    }
    /// Bytes not read yet (unit: bytes).
    std::size_t remaining() const { return m_data.size() - m_at; }
    /// True when every byte was read.
    bool done() const { return m_at == m_data.size(); }
    /// Throws `fluid::Error` "<what>: <message>" with `code` (`ErrorCode::BadFile` unless the
    /// caller knows better: memory that ran out reading a part).
    [[noreturn]] void fail(const std::string& message, ErrorCode code = ErrorCode::BadFile) const {
        throw Error(m_what + ": " + message, code);
    }

private:
    std::string_view take(std::size_t n, const char* field) {
        if (n > remaining()) {
            fail(std::string("truncated (ended while reading ") + field + ")");
        }
        const std::string_view out = m_data.substr(m_at, n);
        m_at += n;
        return out;
    }
    std::string_view m_data;
    std::size_t m_at = 0;
    std::string m_what;
};

/// Writes plain values to a stream as their bytes (Box2D worlds, the coupling's state). One
/// thread at a time.
class StreamWriter {
public:
    /// Writes to `out`.
    explicit StreamWriter(std::ostream& out) : m_out(out) {}
    /// A value as its bytes.
    template <class T> void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        m_out.write(reinterpret_cast<const char*>(&value), sizeof(T));
    }

private:
    std::ostream& m_out;
};

/// Reads what `StreamWriter` wrote, no further than its own fields (a stream may hold more
/// after them). Every error throws `fluid::Error` (`ErrorCode::BadFile`) "<what>: <message>". One
/// thread at a time.
class StreamReader {
public:
    /// Reads `in`; `what` opens every error ("box2d save").
    StreamReader(std::istream& in, std::string what) : m_in(in), m_what(std::move(what)) {}
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
    template <class T> T number(const std::string& field, T lo, T hi, const char* unit = nullptr) {
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
    /// Throws `fluid::Error` (`ErrorCode::BadFile`) "<what>: <message>".
    [[noreturn]] void fail(const std::string& message) const {
        throw Error(m_what + ": " + message, ErrorCode::BadFile);
    }

private:
    std::istream& m_in;
    std::string m_what;
};

} // namespace fluid::internal
