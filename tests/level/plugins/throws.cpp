// A plugin library whose registration fails half way (test_plugin_library.cpp): it registers a
// valid force, then one whose declared default lies outside its range, so Registry::add (the
// module's own copy) throws fluid::Error. The load must fail naming the library, and the host's
// registry must not receive the valid force either.
#include <fluid/plugin_abi.h>

#include <array>

namespace {

class GoodForce : public fluid::ForcePlugin {
public:
    static constexpr std::string_view kType = "force.test_good";
    static constexpr std::array<fluid::ParamDecl, 1> kParams{{
        {"k", "1", 0.5, 0.0, 1.0, "A parameter."},
    }};
    GoodForce() : fluid::ForcePlugin(kType, kParams) {}
    void apply(const fluid::ForceContext&, uint32_t, uint32_t) override {}
};

class BadDefaultForce : public fluid::ForcePlugin {
public:
    static constexpr std::string_view kType = "force.test_bad_default";
    static constexpr std::array<fluid::ParamDecl, 1> kParams{{
        {"k", "1", 5.0, 0.0, 1.0, "Its default is out of range."},
    }};
    BadDefaultForce() : fluid::ForcePlugin(kType, kParams) {}
    void apply(const fluid::ForceContext&, uint32_t, uint32_t) override {}
};

} // namespace

FLUID_PLUGIN_ENTRY(registry) {
    registry.add<GoodForce>("Registered before the failure.");
    registry.add<BadDefaultForce>("Refused by Registry::add.");
}
