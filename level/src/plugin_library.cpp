// fluid::level — loading plugin libraries with dlopen (POSIX). See plugin_library.h.
#include <fluid/plugin_library.h>

#include <dlfcn.h>

#include <cstring>
#include <exception>
#include <sstream>
#include <utility>

namespace fluid {

namespace {

constexpr auto kHostDetails = pluginAbiDetails();

std::string lastDlError() {
    const char* message = dlerror();
    return message != nullptr ? message : "unknown dynamic loader error";
}

// dlsym returns a data pointer; POSIX guarantees it converts to a function pointer.
template <class Fn> Fn findEntry(void* handle, const char* name) {
    void* symbol = dlsym(handle, name);
    Fn fn = nullptr;
    static_assert(sizeof(fn) == sizeof(symbol), "dlsym: function and data pointers differ");
    std::memcpy(&fn, &symbol, sizeof(fn));
    return fn;
}

// Closes a library refused before any of its plugin code ran; libraries whose registration
// ran stay open (the lifetime rule in plugin_library.h).
class OpenLibrary {
public:
    explicit OpenLibrary(void* handle) : m_handle(handle) {}
    ~OpenLibrary() {
        if (m_handle != nullptr) {
            dlclose(m_handle);
        }
    }
    OpenLibrary(const OpenLibrary&) = delete;
    OpenLibrary& operator=(const OpenLibrary&) = delete;
    void* get() const { return m_handle; }
    void keepLoaded() { m_handle = nullptr; }

private:
    void* m_handle;
};

std::string describeDetail(std::size_t index, uint32_t value) {
    const uint32_t family = value / 1000u, rest = value % 1000u;
    if (index == 1) {
        std::ostringstream s;
        s << "0x" << std::hex << value;
        return s.str();
    }
    if (index == 2) {
        static constexpr const char* kNames[] = {"an unknown compiler", "GCC", "Clang", "MSVC"};
        return family < 4 ? std::string(kNames[family]) + " " + std::to_string(rest)
                          : std::to_string(value);
    }
    if (index == 3) {
        switch (family) {
        case 1:
            return std::string("libstdc++") + (rest >= 100 ? " debug mode" : "") +
                   (rest % 100 == 1 ? " (C++11 ABI)" : " (old ABI)");
        case 2:
            return "libc++ ABI " + std::to_string(rest);
        case 3:
            return "MSVC STL (iterator debug level " + std::to_string(rest) + ")";
        default:
            return "an unknown standard library";
        }
    }
    return std::to_string(value);
}

// Throws unless the library's details equal the host's; names the first differing entry.
void checkDetails(const std::string& path, const uint32_t* details) {
    const uint32_t count = details[0];
    if (count != kHostDetails[0]) {
        throw Error("'" + path + "' was built for plugin ABI " + std::to_string(kPluginAbiVersion) +
                        " but does not match this fluid: it reports " + std::to_string(count) +
                        " ABI details, this fluid " + std::to_string(kHostDetails[0]) +
                        ": rebuild the plugin against this fluid",
                    ErrorCode::BadFile);
    }
    for (std::size_t i = 1; i < kHostDetails.size(); ++i) {
        if (details[i] != kHostDetails[i]) {
            throw Error(
                "'" + path + "' was built for plugin ABI " + std::to_string(kPluginAbiVersion) +
                    " but does not match this fluid: " + std::string(kPluginAbiDetailNames[i]) +
                    " is " + describeDetail(i, details[i]) + " in the plugin, " +
                    describeDetail(i, kHostDetails[i]) +
                    " here: rebuild the plugin against this fluid's headers with the same "
                    "compiler and settings",
                ErrorCode::BadFile);
        }
    }
}

} // namespace

PluginLibrary loadPluginLibrary(const std::string& path, Registry& registry) {
    // RTLD_NOW: an unresolved symbol fails here with a message, not later in the middle of a
    // step. RTLD_LOCAL: the library's symbols never satisfy another library's references.
    const std::string openPath = path.find('/') == std::string::npos ? "./" + path : path;
    dlerror(); // clear a stale message
    OpenLibrary library(dlopen(openPath.c_str(), RTLD_NOW | RTLD_LOCAL));
    if (library.get() == nullptr) {
        throw Error("cannot load plugin library '" + path + "': " + lastDlError(), ErrorCode::Io);
    }

    const auto version = findEntry<PluginAbiVersionFn>(library.get(), kPluginAbiVersionSymbol);
    const auto registerPlugins = findEntry<PluginRegisterFn>(library.get(), kPluginRegisterSymbol);
    if (version == nullptr || registerPlugins == nullptr) {
        throw Error("'" + path + "' is not a fluid plugin library: it has no " +
                        kPluginAbiVersionSymbol + " / " + kPluginRegisterSymbol + " entry point",
                    ErrorCode::BadFile);
    }
    // The version entry point's signature is frozen, so calling it is safe whatever the
    // library was built against; nothing else is called until the version and details match.
    const uint32_t libraryVersion = version();
    if (libraryVersion != kPluginAbiVersion) {
        throw Error("'" + path + "' was built for plugin ABI " + std::to_string(libraryVersion) +
                        "; this fluid has ABI " + std::to_string(kPluginAbiVersion) +
                        ": rebuild the plugin against this fluid",
                    ErrorCode::BadFile);
    }
    const auto details = findEntry<PluginAbiDetailsFn>(library.get(), kPluginAbiDetailsSymbol);
    if (details == nullptr) {
        throw Error("'" + path + "' is not a fluid plugin library: it has no " +
                        kPluginAbiDetailsSymbol + " entry point (define the entry points with " +
                        "FLUID_PLUGIN_ENTRY from <fluid/plugin_abi.h>)",
                    ErrorCode::BadFile);
    }
    checkDetails(path, details());

    // From here on the library's code has run: keep it loaded whatever happens (its static
    // objects may be referenced by what it returned or threw).
    library.keepLoaded();
    // All or nothing: register into a scratch registry, then add its types to a copy of the
    // host's registry, which replaces the original only when every type went in.
    Registry scratch;
    try {
        registerPlugins(&scratch);
    } catch (const std::exception& e) {
        throw Error("plugin library '" + path + "': " + kPluginRegisterSymbol +
                        " failed: " + e.what(),
                    dynamic_cast<const Error*>(&e) != nullptr ? static_cast<const Error&>(e).code()
                                                              : ErrorCode::BadArgument);
    } catch (...) {
        throw Error("plugin library '" + path + "': " + kPluginRegisterSymbol +
                        " threw an exception that is not a std::exception",
                    ErrorCode::BadArgument);
    }
    Registry merged = registry;
    PluginLibrary loaded{path, {}};
    for (const PluginInfo& info : scratch.types()) {
        try {
            merged.add(info);
        } catch (const Error& e) {
            throw Error("plugin library '" + path + "': " + e.what(), e.code());
        }
        loaded.types.push_back(info.type);
    }
    registry = std::move(merged);
    return loaded;
}

} // namespace fluid
