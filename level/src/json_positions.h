// fluid::level — private: where things are in a JSON text, and a strict reader over nlohmann
// values that reports every problem as a LevelError with the file, line, column and JSON pointer.
//
// nlohmann 3.11 keeps no source positions in its values. Positions are found only when an error
// is reported: a small scanner walks the same text (already validated by nlohmann) along the
// JSON pointer. Nothing is stored per value, so a large or deeply nested input costs no memory
// beyond nlohmann's own, and the scanner never recurses (deep nesting cannot overflow the stack).
#pragma once

#include <fluid/internal/number_text.h>

#include <fluid/level.h>

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fluid::detail {

using Json = nlohmann::json;

/// A place in a text (unit: 1-based line, 1-based byte column).
struct TextPosition {
    /// Line (1-based).
    uint32_t line = 1;
    /// Byte column (1-based; a tab counts one).
    uint32_t column = 1;
};

/// Line and column of byte `offset` in `text` (offsets past the end give the end).
TextPosition positionOf(std::string_view text, std::size_t offset);

/// Byte offset in the valid JSON `text` of the value at JSON pointer `pointer` (RFC 6901), or,
/// with `key` set, of the member name that leads to it (the pointer's last token must then name
/// an object member). When the pointer leads nowhere, the offset of the deepest value found.
std::size_t locate(std::string_view text, std::string_view pointer, bool key = false);

/// Member names of the object at `pointer` in the valid JSON `text`, in text order (empty when
/// the pointer does not lead to an object).
std::vector<std::string> memberNames(std::string_view text, std::string_view pointer);

/// The scalar token starting at `offset` (a number as written, e.g. "1e999"), for messages.
std::string tokenAt(std::string_view text, std::size_t offset);

/// A member name used twice in one object: the pointer to the second use and the offset of its
/// name in the text.
struct DuplicateKey {
    /// JSON pointer of the second member.
    std::string pointer;
    /// Byte offset of the second member's name.
    std::size_t offset = 0;
};

/// The first member name (in text order) that repeats within its object in the valid JSON
/// `text`, if any. nlohmann keeps the last of the two silently; level files must not.
std::optional<DuplicateKey> findDuplicateKey(std::string_view text);

/// `base` + "/" + `token`, with the token escaped as RFC 6901 says ("~" -> "~0", "/" -> "~1").
std::string childPointer(std::string_view base, std::string_view token);
/// `base` + "/" + the array index.
std::string childPointer(std::string_view base, std::size_t index);

/// Numbers as people write them (fluid/internal/number_text.h).
using internal::formatNumber;

/// "a string", "an object", "null"... for "expected X, got Y" messages.
std::string describeType(const Json& value);

/// Accepted values of a number: [lo, hi] (either end open when asked) in `unit`.
struct Range {
    /// Smallest value (unit: `unit`).
    double lo = 0.0;
    /// Largest value (unit: `unit`).
    double hi = 0.0;
    /// SI unit shown in messages ("m", "m/s", "1", "count").
    std::string_view unit;
    /// True when `lo` itself is not accepted.
    bool loOpen = false;
    /// "[lo, hi] (unit: u)" or "(lo, hi] (unit: u)".
    std::string describe() const;
    /// True when `value` lies inside (false for NaN).
    bool contains(double value) const;
};

/// A parsed level text: the nlohmann document and what is needed to point at its parts.
/// Thread rule: one thread.
class JsonDocument {
public:
    /// Parses `text` strictly (no comments, no trailing data, no repeated member names, no
    /// NUL byte anywhere in it: the whole of `text` is the document). Throws LevelError naming
    /// `file`, line and column for a syntax error, a repeated name or a NUL byte.
    JsonDocument(std::string_view text, std::string_view file);

    /// The whole document.
    const Json& root() const { return m_root; }
    /// The file name used in errors.
    const std::string& file() const { return m_file; }

    /// Throws LevelError at the value at `pointer`, with `code` (ErrorCode::UnknownName for a
    /// name nothing is registered under; ErrorCode::BadFile, the default, for the rest).
    [[noreturn]] void fail(std::string_view pointer, const std::string& message,
                           ErrorCode code = ErrorCode::BadFile) const;
    /// The LevelError at the value at `pointer` with `code`, to throw (`std::throw_with_nested`
    /// keeps what caused it: memory that ran out).
    LevelError errorAt(std::string_view pointer, const std::string& message,
                       ErrorCode code = ErrorCode::BadFile) const;
    /// The text a LevelError at the value at `pointer` would carry, for a warning.
    std::string locatedText(std::string_view pointer, const std::string& message) const;
    /// Throws LevelError at the member name that leads to `pointer`, with `code`.
    [[noreturn]] void failAtKey(std::string_view pointer, const std::string& message,
                                ErrorCode code = ErrorCode::BadFile) const;
    /// Member names of the object at `pointer`, in text order.
    std::vector<std::string> memberNames(std::string_view pointer) const;
    /// Byte offset of the member name that leads to `pointer` (to order members by position).
    std::size_t keyOffset(std::string_view pointer) const;
    /// The number token as written at `pointer` (for "1e999 is not finite").
    std::string tokenAt(std::string_view pointer) const;

private:
    std::string_view m_text;
    std::string m_file;
    Json m_root;
};

/// A JSON object of the level being read: typed, range-checked access to its members, every
/// error located. Thread rule: one thread.
class ObjectReader {
public:
    /// Reads `value` at `pointer`; throws LevelError unless it is an object (`what` names what
    /// the object describes, e.g. "a blob").
    ObjectReader(const JsonDocument& doc, const Json& value, std::string pointer,
                 std::string_view what);

    /// Throws LevelError at the first member (in text order) whose name is not in `allowed`,
    /// listing the allowed names.
    void allowOnly(std::initializer_list<std::string_view> allowed) const;
    /// As above, from a list.
    void allowOnly(const std::vector<std::string_view>& allowed) const;
    /// The first member (in text order) whose name is not in `allowed`, if any.
    std::optional<std::string> firstUnknownKey(const std::vector<std::string_view>& allowed) const;

    /// True when the member exists.
    bool has(std::string_view key) const;
    /// The member, or nullptr.
    const Json* find(std::string_view key) const;
    /// Pointer to the member `key`.
    std::string pointer(std::string_view key) const { return childPointer(m_pointer, key); }
    /// Pointer to this object.
    const std::string& pointer() const { return m_pointer; }
    /// The document (for errors).
    const JsonDocument& document() const { return m_doc; }
    /// Throws LevelError at this object ("missing key 'x'; expected ..."), with `code`.
    [[noreturn]] void fail(const std::string& message, ErrorCode code = ErrorCode::BadFile) const {
        m_doc.fail(m_pointer, message, code);
    }
    /// Throws LevelError at member `key`, with `code`.
    [[noreturn]] void failAt(std::string_view key, const std::string& message,
                             ErrorCode code = ErrorCode::BadFile) const {
        m_doc.fail(pointer(key), message, code);
    }
    /// The member; throws "missing key" (with `expected`) when absent.
    const Json& required(std::string_view key, std::string_view expected) const;

    /// A number in `range`, or `fallback` when absent.
    double number(std::string_view key, const Range& range, double fallback) const;
    /// A number in `range`; throws when absent.
    double requiredNumber(std::string_view key, const Range& range) const;
    /// A whole number in `range`, or `fallback` when absent.
    uint64_t integer(std::string_view key, const Range& range, uint64_t fallback) const;
    /// A string, or `fallback` when absent.
    std::string string(std::string_view key, std::string_view fallback) const;
    /// A string; throws when absent (`expected` says what it names).
    std::string requiredString(std::string_view key, std::string_view expected) const;
    /// A boolean, or `fallback` when absent.
    bool boolean(std::string_view key, bool fallback) const;
    /// A point [x, y], each coordinate in `range`, or `fallback` when absent.
    glm::vec2 point(std::string_view key, const Range& range, glm::vec2 fallback) const;
    /// A point [x, y]; throws when absent.
    glm::vec2 requiredPoint(std::string_view key, const Range& range) const;
    /// A point list [[x, y], ...] of `minCount` to `maxCount` points; throws when absent.
    std::vector<glm::vec2> requiredPoints(std::string_view key, const Range& range,
                                          std::size_t minCount, std::size_t maxCount) const;
    /// The member as an array (empty when absent); throws unless it is an array.
    const Json* array(std::string_view key, std::string_view what) const;

private:
    const JsonDocument& m_doc;
    const Json& m_value;
    std::string m_pointer;
};

/// Checks that `value` at `pointer` is a finite number in `range`; returns it.
double readNumber(const JsonDocument& doc, const Json& value, const std::string& pointer,
                  const Range& range);
/// Checks that `value` at `pointer` is a point list of `minCount` to `maxCount` points with
/// coordinates in `range`; returns it.
std::vector<glm::vec2> readPoints(const JsonDocument& doc, const Json& value,
                                  const std::string& pointer, const Range& range,
                                  std::size_t minCount, std::size_t maxCount);

} // namespace fluid::detail
