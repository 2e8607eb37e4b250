// fluid::level — positions in JSON text and a strict, located reader over nlohmann values.
#include "json_positions.h"

#include <fluid/internal/checks.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>

namespace fluid::detail {

namespace {

// ---- the scanner -------------------------------------------------------------------------
// Runs over text nlohmann has accepted (or, for a parse error, over the valid prefix before the
// error). Every loop advances or stops at the end, so malformed text cannot hang it.

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

class Scanner {
public:
    explicit Scanner(std::string_view text) : m_text(text) {}

    char at(std::size_t p) const { return p < m_text.size() ? m_text[p] : '\0'; }
    std::size_t size() const { return m_text.size(); }

    // nlohmann skips a UTF-8 byte order mark; so do we.
    std::size_t start() const {
        const std::size_t p = m_text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
        return skipSpace(p);
    }

    std::size_t skipSpace(std::size_t p) const {
        while (p < m_text.size() && isSpace(m_text[p])) {
            ++p;
        }
        return p;
    }

    // p at the opening quote; returns the offset after the closing quote.
    std::size_t skipString(std::size_t p) const {
        ++p;
        while (p < m_text.size() && m_text[p] != '"') {
            p += m_text[p] == '\\' ? 2 : 1;
        }
        return std::min(p + 1, m_text.size());
    }

    // p at the opening quote; decodes the string as nlohmann does (escapes, \u with surrogate
    // pairs, to UTF-8) and moves p past it.
    std::string readString(std::size_t& p) const {
        std::string out;
        ++p;
        while (p < m_text.size() && m_text[p] != '"') {
            if (m_text[p] != '\\') {
                out += m_text[p++];
                continue;
            }
            const char e = at(p + 1);
            p += 2;
            static constexpr std::string_view kEscaped = "bfnrt", kMeaning = "\b\f\n\r\t";
            if (const std::size_t k = kEscaped.find(e); k != std::string_view::npos) {
                out += kMeaning[k];
            } else if (e == 'u') {
                uint32_t code = readHex4(p);
                if (code >= 0xD800 && code <= 0xDBFF && at(p) == '\\' && at(p + 1) == 'u') {
                    std::size_t q = p + 2;
                    const uint32_t low = readHex4(q);
                    if (low >= 0xDC00 && low <= 0xDFFF) {
                        code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                        p = q;
                    }
                }
                appendUtf8(out, code);
            } else {
                out += e; // \" \\ \/
            }
        }
        p = std::min(p + 1, m_text.size());
        return out;
    }

    // A number, true, false or null: up to the next delimiter.
    std::size_t skipScalar(std::size_t p) const {
        while (p < m_text.size() && !isSpace(m_text[p]) && m_text[p] != ',' && m_text[p] != ']' &&
               m_text[p] != '}' && m_text[p] != ':') {
            ++p;
        }
        return p;
    }

    // Any value, containers by counting brackets (no recursion).
    std::size_t skipValue(std::size_t p) const {
        const char c = at(p);
        if (c == '"') {
            return skipString(p);
        }
        if (c != '{' && c != '[') {
            return skipScalar(p);
        }
        std::size_t depth = 0;
        while (p < m_text.size()) {
            const char d = m_text[p];
            if (d == '"') {
                p = skipString(p);
                continue;
            }
            if (d == '{' || d == '[') {
                ++depth;
            } else if (d == '}' || d == ']') {
                if (--depth == 0) {
                    return p + 1;
                }
            }
            ++p;
        }
        return p;
    }

    // Past the value at p and the comma after it: true, p at the next element; false at the
    // end of the object or array (no comma), p after the value.
    bool nextElement(std::size_t& p) const {
        p = skipSpace(skipValue(p));
        if (at(p) != ',') {
            return false;
        }
        p = skipSpace(p + 1);
        return true;
    }

private:
    uint32_t readHex4(std::size_t& p) const {
        uint32_t v = 0;
        for (int k = 0; k < 4; ++k, ++p) {
            const char h = at(p);
            v <<= 4;
            if (h >= '0' && h <= '9') {
                v |= uint32_t(h - '0');
            } else if (h >= 'a' && h <= 'f') {
                v |= uint32_t(h - 'a' + 10);
            } else if (h >= 'A' && h <= 'F') {
                v |= uint32_t(h - 'A' + 10);
            }
        }
        return v;
    }

    static void appendUtf8(std::string& out, uint32_t c) {
        if (c < 0x80) {
            out += char(c);
        } else if (c < 0x800) {
            out += char(0xC0 | (c >> 6));
            out += char(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            out += char(0xE0 | (c >> 12));
            out += char(0x80 | ((c >> 6) & 0x3F));
            out += char(0x80 | (c & 0x3F));
        } else {
            out += char(0xF0 | (c >> 18));
            out += char(0x80 | ((c >> 12) & 0x3F));
            out += char(0x80 | ((c >> 6) & 0x3F));
            out += char(0x80 | (c & 0x3F));
        }
    }

    std::string_view m_text;
};

// Visits every value (and member name) in text order, keeping the path to it, without
// recursion. `onValue(offset)` and `onKey(offset, name)` return true to stop the walk.
class Walker {
public:
    explicit Walker(std::string_view text) : m_scan(text) {}

    template <class OnValue, class OnKey> void run(OnValue&& onValue, OnKey&& onKey) {
        std::size_t p = m_scan.start();
        for (;;) {
            // A value starts at p.
            p = m_scan.skipSpace(p);
            if (p >= m_scan.size() || onValue(p)) {
                return;
            }
            const char c = m_scan.at(p);
            bool expectValue = false;
            if (c == '{' || c == '[') {
                m_stack.push_back(Frame{c == '{', 0, {}, {}});
                p = m_scan.skipSpace(p + 1);
                if (m_scan.at(p) == (c == '{' ? '}' : ']')) {
                    ++p;
                    m_stack.pop_back();
                } else if (c == '{') {
                    if (!member(p, onKey)) {
                        return;
                    }
                    expectValue = true;
                } else {
                    expectValue = true;
                }
            } else {
                p = c == '"' ? m_scan.skipString(p) : m_scan.skipScalar(p);
            }
            // After a value: commas and closing brackets until the next value starts.
            while (!expectValue) {
                p = m_scan.skipSpace(p);
                if (m_stack.empty() || p >= m_scan.size()) {
                    return;
                }
                const char d = m_scan.at(p);
                if (d == ',') {
                    p = m_scan.skipSpace(p + 1);
                    if (m_stack.back().object) {
                        if (!member(p, onKey)) {
                            return;
                        }
                    } else {
                        ++m_stack.back().index;
                    }
                    expectValue = true;
                } else if (d == '}' || d == ']') {
                    ++p;
                    m_stack.pop_back();
                } else {
                    return; // not valid JSON past here
                }
            }
        }
    }

    // JSON pointer of the value being visited.
    std::string pointer() const {
        std::string out;
        for (const Frame& f : m_stack) {
            out = f.object ? childPointer(out, f.key) : childPointer(out, f.index);
        }
        return out;
    }

private:
    struct Frame {
        bool object = false;
        std::size_t index = 0;
        std::string key;
        std::set<std::string> seen;
    };

    // p at a member name: reads it (reporting it to onKey) and the colon; false to stop.
    template <class OnKey> bool member(std::size_t& p, OnKey& onKey) {
        if (m_scan.at(p) != '"') {
            return false;
        }
        const std::size_t keyOffset = p;
        Frame& f = m_stack.back();
        f.key = m_scan.readString(p);
        if (onKey(keyOffset, f.key, f.seen)) {
            return false;
        }
        p = m_scan.skipSpace(p);
        if (m_scan.at(p) != ':') {
            return false;
        }
        ++p;
        return true;
    }

    Scanner m_scan;
    std::vector<Frame> m_stack;
};

std::vector<std::string> splitPointer(std::string_view pointer) {
    std::vector<std::string> tokens;
    std::size_t p = 0;
    while (p < pointer.size() && pointer[p] == '/') {
        const std::size_t end = std::min(pointer.find('/', p + 1), pointer.size());
        std::string token;
        for (std::size_t k = p + 1; k < end; ++k) {
            if (pointer[k] == '~' && k + 1 < end &&
                (pointer[k + 1] == '0' || pointer[k + 1] == '1')) {
                token += pointer[k + 1] == '0' ? '~' : '/';
                ++k;
            } else {
                token += pointer[k];
            }
        }
        tokens.push_back(std::move(token));
        p = end;
    }
    return tokens;
}

bool parseIndex(const std::string& token, std::size_t& index) {
    if (token.empty() || token.size() > 18) {
        return false;
    }
    index = 0;
    for (const char c : token) {
        if (c < '0' || c > '9') {
            return false;
        }
        index = index * 10 + std::size_t(c - '0');
    }
    return true;
}

// nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 7: syntax error
// ..." without the parts the LevelError prefix already says.
std::string stripNlohmannPrefix(const std::string& what) {
    const std::size_t at = what.find("parse error at line ");
    if (at != std::string::npos) {
        const std::size_t colon = what.find(": ", at);
        if (colon != std::string::npos) {
            return what.substr(colon + 2);
        }
    }
    const std::size_t bracket = what.find("] ");
    return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

// nlohmann's DOM builder, plus the position and message of the first parse error (nlohmann's
// out_of_range for an overflowing number carries no position; the SAX callback does).
class LocatingDomParser {
public:
    explicit LocatingDomParser(Json& result) : m_dom(result, false) {}

    bool null() { return m_dom.null(); }
    bool boolean(bool v) { return m_dom.boolean(v); }
    bool number_integer(Json::number_integer_t v) { return m_dom.number_integer(v); }
    bool number_unsigned(Json::number_unsigned_t v) { return m_dom.number_unsigned(v); }
    bool number_float(Json::number_float_t v, const std::string& s) {
        return m_dom.number_float(v, s);
    }
    bool string(std::string& v) { return m_dom.string(v); }
    bool binary(Json::binary_t& v) { return m_dom.binary(v); }
    bool start_object(std::size_t n) { return m_dom.start_object(n); }
    bool key(std::string& v) { return m_dom.key(v); }
    bool end_object() { return m_dom.end_object(); }
    bool start_array(std::size_t n) { return m_dom.start_array(n); }
    bool end_array() { return m_dom.end_array(); }
    bool parse_error(std::size_t position, const std::string& lastToken,
                     const nlohmann::detail::exception& ex) {
        errorEnd = position;
        errorId = ex.id;
        errorToken = lastToken;
        errorMessage = stripNlohmannPrefix(ex.what());
        return false;
    }

    std::size_t errorEnd = 0;
    int errorId = 0;
    std::string errorToken;
    std::string errorMessage;

private:
    nlohmann::detail::json_sax_dom_parser<Json> m_dom;
};

} // namespace

// ---- positions ---------------------------------------------------------------------------

TextPosition positionOf(std::string_view text, std::size_t offset) {
    offset = std::min(offset, text.size());
    TextPosition pos;
    std::size_t lineStart = 0;
    for (std::size_t k = 0; k < offset; ++k) {
        if (text[k] == '\n') {
            ++pos.line;
            lineStart = k + 1;
        }
    }
    pos.column = uint32_t(offset - lineStart + 1);
    return pos;
}

std::size_t locate(std::string_view text, std::string_view pointer, bool key) {
    const Scanner scan(text);
    const std::vector<std::string> tokens = splitPointer(pointer);
    std::size_t pos = scan.start();
    for (std::size_t t = 0; t < tokens.size(); ++t) {
        const bool last = t + 1 == tokens.size();
        const char c = scan.at(pos);
        bool found = false;
        if (c == '{') {
            std::size_t p = scan.skipSpace(pos + 1);
            while (scan.at(p) == '"') {
                const std::size_t keyOffset = p;
                const std::string name = scan.readString(p);
                p = scan.skipSpace(p);
                p = scan.skipSpace(scan.at(p) == ':' ? p + 1 : p);
                if (name == tokens[t]) {
                    if (last && key) {
                        return keyOffset;
                    }
                    pos = p;
                    found = true;
                    break;
                }
                if (!scan.nextElement(p)) {
                    break;
                }
            }
        } else if (c == '[') {
            std::size_t index = 0;
            if (parseIndex(tokens[t], index)) {
                std::size_t p = scan.skipSpace(pos + 1);
                for (std::size_t n = 0; p < scan.size() && scan.at(p) != ']'; ++n) {
                    if (n == index) {
                        pos = p;
                        found = true;
                        break;
                    }
                    if (!scan.nextElement(p)) {
                        break;
                    }
                }
            }
        }
        if (!found) {
            return pos;
        }
    }
    return pos;
}

std::vector<std::string> memberNames(std::string_view text, std::string_view pointer) {
    const Scanner scan(text);
    std::vector<std::string> names;
    std::size_t p = locate(text, pointer, false);
    if (scan.at(p) != '{') {
        return names;
    }
    p = scan.skipSpace(p + 1);
    while (scan.at(p) == '"') {
        names.push_back(scan.readString(p));
        p = scan.skipSpace(p);
        p = scan.skipSpace(scan.at(p) == ':' ? p + 1 : p);
        if (!scan.nextElement(p)) {
            break;
        }
    }
    return names;
}

std::string tokenAt(std::string_view text, std::size_t offset) {
    const Scanner scan(text);
    const std::size_t end = std::min(scan.skipScalar(offset), offset + 64);
    return std::string(text.substr(std::min(offset, text.size()), end - offset));
}

std::optional<DuplicateKey> findDuplicateKey(std::string_view text) {
    std::optional<DuplicateKey> found;
    Walker walker(text);
    walker.run([](std::size_t) { return false; },
               [&](std::size_t offset, const std::string& name, std::set<std::string>& seen) {
                   if (seen.insert(name).second) {
                       return false;
                   }
                   found = DuplicateKey{walker.pointer(), offset};
                   return true;
               });
    return found;
}

std::string childPointer(std::string_view base, std::string_view token) {
    std::string out(base);
    out += '/';
    for (const char c : token) {
        if (c == '~') {
            out += "~0";
        } else if (c == '/') {
            out += "~1";
        } else {
            out += c;
        }
    }
    return out;
}

std::string childPointer(std::string_view base, std::size_t index) {
    return std::string(base) + '/' + std::to_string(index);
}

std::string describeType(const Json& value) {
    switch (value.type()) {
    case Json::value_t::null:
        return "null";
    case Json::value_t::object:
        return "an object";
    case Json::value_t::array:
        return "an array";
    case Json::value_t::string:
        return "a string";
    case Json::value_t::boolean:
        return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
        return "a number";
    default:
        return "a value";
    }
}

std::string Range::describe() const {
    return std::string(loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
           "] (unit: " + std::string(unit) + ")";
}

bool Range::contains(double value) const {
    return (loOpen ? value > lo : value >= lo) && value <= hi;
}

// ---- the document ------------------------------------------------------------------------

JsonDocument::JsonDocument(std::string_view text, std::string_view file)
    : m_text(text), m_file(file) {
    // The JSON reader takes a NUL byte for the end of the text: "{...}\0garbage" would load.
    // The whole text is the document, and JSON text holds no NUL byte.
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        const TextPosition pos = positionOf(text, nul);
        throw LevelError(m_file, pos.line, pos.column, "",
                         "a NUL byte at byte offset " + std::to_string(nul) + " of the " +
                             std::to_string(text.size()) +
                             "-byte text; a level file is JSON text and holds none");
    }
    LocatingDomParser sax(m_root);
    if (!Json::sax_parse(text.begin(), text.end(), &sax)) {
        std::size_t offset = sax.errorEnd > 0 ? sax.errorEnd - 1 : 0;
        if (sax.errorId == 406) {
            // A number too large for a double (1e999): name the value and where it sits. The
            // text before it is valid, so the walker finds the last value starting before the
            // error's end.
            std::string pointer;
            std::size_t start = 0;
            Walker walker(text);
            walker.run(
                [&](std::size_t at) {
                    if (at >= sax.errorEnd) {
                        return true;
                    }
                    start = at;
                    pointer = walker.pointer();
                    return false;
                },
                [](std::size_t, const std::string&, std::set<std::string>&) { return false; });
            const TextPosition pos = positionOf(text, start);
            throw LevelError(m_file, pos.line, pos.column, pointer,
                             sax.errorToken + " is not finite (it overflows a double); expected "
                                              "a finite number");
        }
        const TextPosition pos = positionOf(text, offset);
        throw LevelError(m_file, pos.line, pos.column, "", sax.errorMessage);
    }
    if (const std::optional<DuplicateKey> dup = findDuplicateKey(text)) {
        const TextPosition pos = positionOf(text, dup->offset);
        const std::size_t slash = dup->pointer.rfind('/');
        const std::vector<std::string> tokens = splitPointer(dup->pointer.substr(slash));
        throw LevelError(m_file, pos.line, pos.column, dup->pointer,
                         "duplicate key " +
                             internal::quoted(tokens.empty() ? std::string() : tokens[0]) +
                             "; each key may appear once per object");
    }
}

void JsonDocument::fail(std::string_view pointer, const std::string& message,
                        ErrorCode code) const {
    throw errorAt(pointer, message, code);
}

LevelError JsonDocument::errorAt(std::string_view pointer, const std::string& message,
                                 ErrorCode code) const {
    const TextPosition pos = positionOf(m_text, locate(m_text, pointer, false));
    return LevelError(m_file, pos.line, pos.column, std::string(pointer), message, code);
}

std::string JsonDocument::locatedText(std::string_view pointer, const std::string& message) const {
    const TextPosition pos = positionOf(m_text, locate(m_text, pointer, false));
    return LevelError(m_file, pos.line, pos.column, std::string(pointer), message).what();
}

void JsonDocument::failAtKey(std::string_view pointer, const std::string& message,
                             ErrorCode code) const {
    const TextPosition pos = positionOf(m_text, locate(m_text, pointer, true));
    throw LevelError(m_file, pos.line, pos.column, std::string(pointer), message, code);
}

std::vector<std::string> JsonDocument::memberNames(std::string_view pointer) const {
    return detail::memberNames(m_text, pointer);
}

std::size_t JsonDocument::keyOffset(std::string_view pointer) const {
    return locate(m_text, pointer, true);
}

std::string JsonDocument::tokenAt(std::string_view pointer) const {
    return detail::tokenAt(m_text, locate(m_text, pointer, false));
}

// ---- typed access ------------------------------------------------------------------------

double readNumber(const JsonDocument& doc, const Json& value, const std::string& pointer,
                  const Range& range) {
    if (!value.is_number()) {
        doc.fail(pointer,
                 "expected a number in " + range.describe() + ", got " + describeType(value));
    }
    const double v = value.get<double>();
    if (!std::isfinite(v)) {
        // nlohmann rejects overflowing literals itself; kept for values built other ways.
        doc.fail(pointer,
                 doc.tokenAt(pointer) + " is not finite; expected a number in " + range.describe());
    }
    if (!range.contains(v)) {
        doc.fail(pointer, formatNumber(v) + " is out of range " + range.describe());
    }
    return v;
}

std::vector<glm::vec2> readPoints(const JsonDocument& doc, const Json& value,
                                  const std::string& pointer, const Range& range,
                                  std::size_t minCount, std::size_t maxCount) {
    const std::string expected = "a list of " + std::to_string(minCount) + " to " +
                                 std::to_string(maxCount) +
                                 " points [[x, y], ...] (unit: " + std::string(range.unit) + ")";
    if (!value.is_array()) {
        doc.fail(pointer, "expected " + expected + ", got " + describeType(value));
    }
    if (value.size() < minCount || value.size() > maxCount) {
        doc.fail(pointer, "expected " + expected + ", got " + std::to_string(value.size()) +
                              (value.size() == 1 ? " point" : " points"));
    }
    std::vector<glm::vec2> points;
    points.reserve(value.size());
    for (std::size_t k = 0; k < value.size(); ++k) {
        const Json& p = value[k];
        const std::string at = childPointer(pointer, k);
        if (!p.is_array() || p.size() != 2) {
            doc.fail(at, "expected a point [x, y] of two numbers (unit: " +
                             std::string(range.unit) + "), got " +
                             (p.is_array() ? "an array of " + std::to_string(p.size())
                                           : describeType(p)));
        }
        const double x = readNumber(doc, p[0], childPointer(at, std::size_t(0)), range);
        const double y = readNumber(doc, p[1], childPointer(at, std::size_t(1)), range);
        points.emplace_back(float(x), float(y));
    }
    return points;
}

ObjectReader::ObjectReader(const JsonDocument& doc, const Json& value, std::string pointer,
                           std::string_view what)
    : m_doc(doc), m_value(value), m_pointer(std::move(pointer)) {
    if (!value.is_object()) {
        m_doc.fail(m_pointer,
                   "expected " + std::string(what) + " (an object), got " + describeType(value));
    }
}

void ObjectReader::allowOnly(std::initializer_list<std::string_view> allowed) const {
    allowOnly(std::vector<std::string_view>(allowed));
}

void ObjectReader::allowOnly(const std::vector<std::string_view>& allowed) const {
    const std::optional<std::string> unknown = firstUnknownKey(allowed);
    if (!unknown) {
        return;
    }
    std::string list;
    for (const std::string_view name : allowed) {
        list += (list.empty() ? "" : ", ") + std::string(name);
    }
    m_doc.failAtKey(pointer(*unknown),
                    "unknown key " + internal::quoted(*unknown) + "; allowed: " + list);
}

std::optional<std::string>
ObjectReader::firstUnknownKey(const std::vector<std::string_view>& allowed) const {
    // nlohmann sorts members by name; the first unknown one is found in text order, in one
    // pass over the object's text.
    bool anyUnknown = false;
    for (const auto& item : m_value.items()) {
        anyUnknown =
            anyUnknown || std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end();
    }
    if (!anyUnknown) {
        return std::nullopt;
    }
    for (const std::string& name : m_doc.memberNames(m_pointer)) {
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
            return name;
        }
    }
    return std::nullopt;
}

bool ObjectReader::has(std::string_view key) const {
    return find(key) != nullptr;
}

const Json* ObjectReader::find(std::string_view key) const {
    const auto it = m_value.find(key);
    return it == m_value.end() ? nullptr : &*it;
}

const Json& ObjectReader::required(std::string_view key, std::string_view expected) const {
    const Json* value = find(key);
    if (value == nullptr) {
        fail("missing key '" + std::string(key) + "'; expected " + std::string(expected));
    }
    return *value;
}

double ObjectReader::number(std::string_view key, const Range& range, double fallback) const {
    const Json* value = find(key);
    return value == nullptr ? fallback : readNumber(m_doc, *value, pointer(key), range);
}

double ObjectReader::requiredNumber(std::string_view key, const Range& range) const {
    return readNumber(m_doc, required(key, "a number in " + range.describe()), pointer(key), range);
}

uint64_t ObjectReader::integer(std::string_view key, const Range& range, uint64_t fallback) const {
    const Json* value = find(key);
    if (value == nullptr) {
        return fallback;
    }
    const std::string at = pointer(key);
    const std::string expected = "a whole number in " + range.describe();
    if (!value->is_number()) {
        m_doc.fail(at, "expected " + expected + ", got " + describeType(*value));
    }
    // Unsigned 64-bit values (seeds) are exact only as integers; doubles above 2^53 lose digits.
    // The bounds are compared as integers too: as a double, 2^53 + 1 rounds to 2^53 and would
    // pass a range that ends at 2^53.
    if (value->is_number_unsigned()) {
        const uint64_t u = value->get<uint64_t>();
        constexpr double kTwo64 = 18446744073709551616.0;
        const bool belowLo = range.lo >= kTwo64 ||
                             (range.lo > 0.0 && u < uint64_t(std::ceil(range.lo))) ||
                             (range.loOpen && range.lo >= 0.0 && range.lo == std::floor(range.lo) &&
                              u == uint64_t(range.lo));
        const bool aboveHi =
            range.hi < 0.0 || (range.hi < kTwo64 && u > uint64_t(std::floor(range.hi)));
        if (belowLo || aboveHi) {
            m_doc.fail(at, std::to_string(u) + " is out of range " + range.describe());
        }
        return u;
    }
    const double v = readNumber(m_doc, *value, at, range);
    if (v != std::floor(v)) {
        m_doc.fail(at, "expected " + expected + ", got " + formatNumber(v));
    }
    // Ranges are checked above; this keeps the conversion defined whatever range a caller gives.
    if (!(v >= 0.0 && v < 18446744073709551616.0)) {
        m_doc.fail(at, formatNumber(v) + " is out of range " + range.describe());
    }
    return uint64_t(v);
}

std::string ObjectReader::string(std::string_view key, std::string_view fallback) const {
    const Json* value = find(key);
    if (value == nullptr) {
        return std::string(fallback);
    }
    if (!value->is_string()) {
        failAt(key, "expected a string, got " + describeType(*value));
    }
    return value->get<std::string>();
}

std::string ObjectReader::requiredString(std::string_view key, std::string_view expected) const {
    const Json& value = required(key, expected);
    if (!value.is_string()) {
        failAt(key, "expected " + std::string(expected) + ", got " + describeType(value));
    }
    return value.get<std::string>();
}

bool ObjectReader::boolean(std::string_view key, bool fallback) const {
    const Json* value = find(key);
    if (value == nullptr) {
        return fallback;
    }
    if (!value->is_boolean()) {
        failAt(key, "expected true or false, got " + describeType(*value));
    }
    return value->get<bool>();
}

glm::vec2 ObjectReader::point(std::string_view key, const Range& range, glm::vec2 fallback) const {
    const Json* value = find(key);
    if (value == nullptr) {
        return fallback;
    }
    const std::string at = pointer(key);
    if (!value->is_array() || value->size() != 2) {
        m_doc.fail(at, "expected a point [x, y] of two numbers in " + range.describe() + ", got " +
                           (value->is_array() ? "an array of " + std::to_string(value->size())
                                              : describeType(*value)));
    }
    const double x = readNumber(m_doc, (*value)[0], childPointer(at, std::size_t(0)), range);
    const double y = readNumber(m_doc, (*value)[1], childPointer(at, std::size_t(1)), range);
    return {float(x), float(y)};
}

glm::vec2 ObjectReader::requiredPoint(std::string_view key, const Range& range) const {
    required(key, "a point [x, y] of two numbers in " + range.describe());
    return point(key, range, {});
}

std::vector<glm::vec2> ObjectReader::requiredPoints(std::string_view key, const Range& range,
                                                    std::size_t minCount,
                                                    std::size_t maxCount) const {
    const Json& value =
        required(key, "a list of points [[x, y], ...] (unit: " + std::string(range.unit) + ")");
    return readPoints(m_doc, value, pointer(key), range, minCount, maxCount);
}

const Json* ObjectReader::array(std::string_view key, std::string_view what) const {
    const Json* value = find(key);
    if (value != nullptr && !value->is_array()) {
        failAt(key, "expected an array of " + std::string(what) + ", got " + describeType(*value));
    }
    return value;
}

} // namespace fluid::detail
