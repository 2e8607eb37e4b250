// fluid — 2D SPH liquid for games. The binary contract between fluid and plugin libraries.
//
// A plugin library is a shared library (a CMake MODULE) that defines, with C linkage:
//   uint32_t fluid_plugin_abi_version(void);            // frozen forever: kPluginAbiVersion
//   const uint32_t* fluid_plugin_abi_details(void);     // pluginAbiDetails() as the plugin saw it
//   void fluid_register_plugins(fluid::Registry*);       // adds the library's plugin types
// `FLUID_PLUGIN_ENTRY` writes all three. The loader (fluid::loadPluginLibrary in
// <fluid/plugin_library.h>, target fluid::level) calls the first two, which only return
// constants, and refuses the library unless both match this build before calling the third.
// Guide: docs/plugins.md.
#pragma once

#include <fluid/registry.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace fluid {

/// Version of the plugin binary interface. Bump it whenever a change to plugin.h, registry.h,
/// material.h or error.h changes what a compiled plugin sees: a class or struct layout, a
/// virtual function (added, removed, reordered, signature), an inline function's behaviour
/// that both sides must agree on, or the entry points below. The test "the plugin ABI
/// declaration hash is current" fails when the declarations of plugin.h and registry.h change,
/// as a reminder. 4: `Material` gained the yield-stress fields (plugins see it in their
/// contexts). 5: `BoundaryPlugin` gained `rigidBodies` and `receiveBodyImpulses` (bodies in the
/// coarse pressure solve). 6: `BoundaryPlugin` gained `steppedBy` (a plugin whose host must step
/// the world). 7: `Plugin` gained `checkParams`, and `Error` writes control characters as
/// "\xNN". 8: `RigidBody` gained `contacts` (contact events). 9: `ProjectContext` gained
/// `bodyShifts` (where the coarse solve has moved a plugin's rigid bodies). Thread rule: a
/// constant.
inline constexpr uint32_t kPluginAbiVersion = 9;

/// FNV-1a (32 bit) of the declarations of fluid/plugin.h and fluid/registry.h with `//`
/// comments and all whitespace removed (see `pluginAbiDeclHash`). Part of
/// `pluginAbiDetails()`, so a plugin compiled against other declarations is refused even when
/// `kPluginAbiVersion` was not bumped. Update it when that test says so. Thread rule: a constant.
inline constexpr uint32_t kPluginAbiDeclHash = 0xe99fa511u;

/// Name of the entry point returning the library's `kPluginAbiVersion` (C linkage, signature
/// `uint32_t(void)`, frozen for every future ABI version).
inline constexpr const char* kPluginAbiVersionSymbol = "fluid_plugin_abi_version";
/// Name of the entry point returning the library's `pluginAbiDetails()` (C linkage, signature
/// `const uint32_t*(void)`); read only after the version matched.
inline constexpr const char* kPluginAbiDetailsSymbol = "fluid_plugin_abi_details";
/// Name of the registration entry point (C linkage, signature `void(fluid::Registry*)`); called
/// once per load, on the loading thread, with an empty registry.
inline constexpr const char* kPluginRegisterSymbol = "fluid_register_plugins";

/// Signature of the `kPluginAbiVersionSymbol` entry point.
using PluginAbiVersionFn = uint32_t (*)();
/// Signature of the `kPluginAbiDetailsSymbol` entry point.
using PluginAbiDetailsFn = const uint32_t* (*)();
/// Signature of the `kPluginRegisterSymbol` entry point.
using PluginRegisterFn = void (*)(Registry*);

/// What `pluginAbiDetails()` holds, one name per entry, in order (for error messages). Entry 0
/// is the entry count itself, so a reader never reads past a shorter array.
inline constexpr std::array<std::string_view, 22> kPluginAbiDetailNames{{
    "detail count",
    "declaration hash (kPluginAbiDeclHash)",
    "compiler (family * 1000 + major version)",
    "C++ standard library (kind * 1000 + ABI flags)",
    "sizeof(void*)",
    "sizeof(fluid::Plugin)",
    "sizeof(fluid::ForcePlugin)",
    "sizeof(fluid::BoundaryPlugin)",
    "sizeof(fluid::ParamDecl)",
    "sizeof(fluid::PluginInfo)",
    "sizeof(fluid::Registry)",
    "sizeof(fluid::ParticleView)",
    "sizeof(fluid::ForceContext)",
    "sizeof(fluid::StepContext)",
    "sizeof(fluid::ProjectContext)",
    "sizeof(fluid::BoundarySamples)",
    "sizeof(fluid::Material)",
    "sizeof(fluid::Error)",
    "sizeof(fluid::StateReader)",
    "sizeof(std::string)",
    "sizeof(std::function<std::unique_ptr<fluid::Plugin>()>)",
    "alignof(std::max_align_t)",
}};

/// Compiler family and major version as seen by the including translation unit: GCC 1000 +
/// major, Clang 2000 + major, MSVC 3000 + _MSC_VER / 100, other 0. A plugin built by another
/// compiler (or major version) is refused: their C++ ABIs are only mostly compatible.
constexpr uint32_t pluginAbiCompiler() {
#if defined(__clang__)
    return 2000u + uint32_t(__clang_major__);
#elif defined(__GNUC__)
    return 1000u + uint32_t(__GNUC__);
#elif defined(_MSC_VER)
    return 3000u + uint32_t(_MSC_VER / 100);
#else
    return 0u;
#endif
}

/// C++ standard library and the flags that change its layout: libstdc++ 1000 + dual-ABI flag
/// (+ 100 in debug mode), libc++ 2000 + ABI version, MSVC STL 3000 + debug level, other 0.
constexpr uint32_t pluginAbiStdLib() {
#if defined(_LIBCPP_VERSION)
    return 2000u + uint32_t(_LIBCPP_ABI_VERSION);
#elif defined(__GLIBCXX__)
#if defined(_GLIBCXX_DEBUG)
    return 1100u + uint32_t(_GLIBCXX_USE_CXX11_ABI);
#else
    return 1000u + uint32_t(_GLIBCXX_USE_CXX11_ABI);
#endif
#elif defined(_MSVC_STL_VERSION)
    return 3000u + uint32_t(_ITERATOR_DEBUG_LEVEL);
#else
    return 0u;
#endif
}

/// Cheap fingerprint of everything a plugin and its host must agree on beyond the version:
/// the declarations' hash, the compiler and standard library, and the sizes of the structs
/// that cross the boundary. Computed at compile time on each side; the loader compares them
/// entry by entry (names in `kPluginAbiDetailNames`). Thread rule: a constant expression.
constexpr std::array<uint32_t, kPluginAbiDetailNames.size()> pluginAbiDetails() {
    return {{
        uint32_t(kPluginAbiDetailNames.size()),
        kPluginAbiDeclHash,
        pluginAbiCompiler(),
        pluginAbiStdLib(),
        uint32_t(sizeof(void*)),
        uint32_t(sizeof(Plugin)),
        uint32_t(sizeof(ForcePlugin)),
        uint32_t(sizeof(BoundaryPlugin)),
        uint32_t(sizeof(ParamDecl)),
        uint32_t(sizeof(PluginInfo)),
        uint32_t(sizeof(Registry)),
        uint32_t(sizeof(ParticleView)),
        uint32_t(sizeof(ForceContext)),
        uint32_t(sizeof(StepContext)),
        uint32_t(sizeof(ProjectContext)),
        uint32_t(sizeof(BoundarySamples)),
        uint32_t(sizeof(Material)),
        uint32_t(sizeof(Error)),
        uint32_t(sizeof(StateReader)),
        uint32_t(sizeof(std::string)),
        uint32_t(sizeof(std::function<std::unique_ptr<Plugin>()>)),
        uint32_t(alignof(std::max_align_t)),
    }};
}
// Every entry filled: a name added without its value would leave a zero at the end.
static_assert(pluginAbiDetails().back() != 0, "pluginAbiDetails: one value per detail name");

/// The hash behind `kPluginAbiDeclHash`: FNV-1a (32 bit) of `text` after dropping `//`
/// comments (to the end of the line) and every whitespace character, so comments and
/// reformatting do not change it. Callers concatenate plugin.h then registry.h.
/// Thread rule: pure.
constexpr uint32_t pluginAbiDeclHash(std::string_view text) {
    uint32_t hash = 2166136261u;
    bool comment = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (comment) {
            comment = c != '\n';
            continue;
        }
        if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            comment = true;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
            continue;
        }
        hash = (hash ^ uint32_t(uint8_t(c))) * 16777619u;
    }
    return hash;
}

} // namespace fluid

/// Marks an entry point as exported from the plugin library (the rest of a plugin library
/// should be built with hidden visibility; see docs/plugins.md).
#if defined(_WIN32)
#define FLUID_PLUGIN_EXPORT __declspec(dllexport)
#else
#define FLUID_PLUGIN_EXPORT __attribute__((visibility("default")))
#endif

/// Defines a plugin library's three entry points; follow it with the body of the registration
/// function, which receives `fluid::Registry& registry_name`:
///
///     FLUID_PLUGIN_ENTRY(registry) {
///         registry.add<MyForce>("What it does.");
///     }
///
/// Use it once per library, at namespace scope. The body runs on the loading thread with an
/// empty scratch registry; it may throw `fluid::Error` (the load then fails and the host's
/// registry is left unchanged).
#define FLUID_PLUGIN_ENTRY(registry_name)                                                          \
    static void fluidPluginRegisterBody(::fluid::Registry& registry_name);                         \
    extern "C" FLUID_PLUGIN_EXPORT uint32_t fluid_plugin_abi_version() {                           \
        return ::fluid::kPluginAbiVersion;                                                         \
    }                                                                                              \
    extern "C" FLUID_PLUGIN_EXPORT const uint32_t* fluid_plugin_abi_details() {                    \
        static constexpr auto kDetails = ::fluid::pluginAbiDetails();                              \
        return kDetails.data();                                                                    \
    }                                                                                              \
    extern "C" FLUID_PLUGIN_EXPORT void fluid_register_plugins(::fluid::Registry* registry) {      \
        fluidPluginRegisterBody(*registry);                                                        \
    }                                                                                              \
    static void fluidPluginRegisterBody(::fluid::Registry& registry_name)
