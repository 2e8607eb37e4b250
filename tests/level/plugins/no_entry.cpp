// A shared library that is not a fluid plugin library: it exports a function, but none of the
// FLUID_PLUGIN_ENTRY entry points. loadPluginLibrary must refuse it (test_plugin_library.cpp).
extern "C" __attribute__((visibility("default"))) int fluid_test_not_a_plugin() {
    return 42;
}
