// A plugin library built "for another fluid" (test_plugin_library.cpp). By default it reports
// plugin ABI 999; with FLUID_TEST_WRONG_DETAILS it reports this ABI version but a
// sizeof(fluid::Plugin) 8 bytes larger, as a library built against edited headers would. The
// loader must refuse both before registration: fluid_register_plugins aborts the test process.
#include <fluid/plugin_abi.h>

#include <cstdlib>

#ifdef FLUID_TEST_WRONG_DETAILS
extern "C" FLUID_PLUGIN_EXPORT uint32_t fluid_plugin_abi_version() {
    return fluid::kPluginAbiVersion;
}

extern "C" FLUID_PLUGIN_EXPORT const uint32_t* fluid_plugin_abi_details() {
    static const auto kDetails = [] {
        auto details = fluid::pluginAbiDetails();
        details[5] += 8; // sizeof(fluid::Plugin)
        return details;
    }();
    return kDetails.data();
}
#else
extern "C" FLUID_PLUGIN_EXPORT uint32_t fluid_plugin_abi_version() {
    return 999;
}
#endif

extern "C" FLUID_PLUGIN_EXPORT void fluid_register_plugins(fluid::Registry* /*registry*/) {
    std::abort(); // never reached: the loader checks the ABI first
}
