// fluid::level — private: the names a level file gives things (unique per list, looked up by
// references) and errors of the world re-located at the block of the file that caused them.
// Shared by the level reader (level.cpp) and the Box2D bodies reader (bodies.cpp).
#pragma once

#include "json_positions.h"

#include <fluid/internal/checks.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fluid::detail {

// The required, non-empty "name" of a block, printable text (no control characters); `what`
// names the block in the message.
inline std::string requiredName(const ObjectReader& o, std::string_view what) {
    const std::string name =
        o.requiredString("name", "the " + std::string(what) + "'s name (a string)");
    if (name.empty()) {
        o.failAt("name", "expected a non-empty name");
    }
    if (const std::string problem = internal::nameProblem(name); !problem.empty()) {
        o.failAt("name", problem);
    }
    return name;
}

// "a, b, c" for messages; long lists are cut ("... and 40 more").
inline std::string joined(const std::vector<std::string>& names) {
    constexpr std::size_t kShown = 20;
    if (names.empty()) {
        return "(none)";
    }
    std::string out;
    for (std::size_t k = 0; k < names.size() && k < kShown; ++k) {
        out += (k == 0 ? "" : ", ") + names[k];
    }
    if (names.size() > kShown) {
        out += " and " + std::to_string(names.size() - kShown) + " more";
    }
    return out;
}

// Names of one list of the file (materials, sensors...): unique, looked up by references.
template <class Id> class NameTable {
public:
    explicit NameTable(std::string_view what) : m_what(what) {}

    void add(const JsonDocument& doc, const std::string& name, const std::string& pointer, Id id) {
        const auto [it, added] = m_index.emplace(name, m_entries.size());
        if (!added) {
            doc.fail(pointer, "duplicate " + std::string(m_what) + " name " +
                                  internal::quoted(name) + " (first used at " +
                                  m_entries[it->second].pointer + "); names must be unique");
        }
        m_entries.push_back({name, pointer, id});
    }

    Id find(const JsonDocument& doc, const std::string& name, const std::string& pointer) const {
        if (const auto it = m_index.find(name); it != m_index.end()) {
            return m_entries[it->second].id;
        }
        std::vector<std::string> known;
        for (const Entry& e : m_entries) {
            known.push_back(e.name);
        }
        doc.fail(pointer,
                 "unknown " + std::string(m_what) + " " + internal::quoted(name) +
                     "; known: " + joined(known),
                 ErrorCode::UnknownName);
    }

private:
    struct Entry {
        std::string name;
        std::string pointer;
        Id id;
    };
    std::string_view m_what;
    std::vector<Entry> m_entries;
    std::map<std::string, std::size_t> m_index;
};

// Memory a world takes per particle while it steps (unit: bytes; bench/scaling.md measures
// about 194, the program included).
inline constexpr double kBytesPerParticle = 200.0;

// The text of a load error for memory that ran out while the world made room for `particles`
// more particles (unit: count; `whose` names them: "the blob's") on top of `held`.
inline std::string outOfMemoryText(std::string_view whose, double particles, uint64_t held) {
    const double total = particles + double(held);
    const double bytes = total * kBytesPerParticle;
    char gigabytes[32];
    std::snprintf(gigabytes, sizeof gigabytes, "%.1f", bytes / 1e9);
    return "memory ran out making room for " + std::string(whose) + " about " +
           std::to_string(uint64_t(particles)) + " particles: the world would hold about " +
           std::to_string(uint64_t(total)) + " particles, about " +
           std::to_string(uint64_t(bytes)) + " bytes (" + gigabytes + " GB at about " +
           std::to_string(int(kBytesPerParticle)) +
           " bytes per particle); make them fewer or lower world.maxParticles";
}

// A fluid::Error from the world, re-thrown at the block of the file that caused it, with the
// world's error nested in it; its code is ErrorCode::BadFile (the file gave the world a value it
// refuses), or ErrorCode::OutOfMemory for memory that ran out.
template <class F> auto located(const JsonDocument& doc, const std::string& pointer, F&& f) {
    try {
        return f();
    } catch (const LevelError&) {
        throw;
    } catch (const Error& e) {
        // The world refused a value the file gave it: the file's fault, unless memory ran out.
        std::throw_with_nested(doc.errorAt(
            pointer, e.what(),
            e.code() == ErrorCode::OutOfMemory ? ErrorCode::OutOfMemory : ErrorCode::BadFile));
    }
}

} // namespace fluid::detail
