// fluid::gl embedded shaders and styling helpers (no context needed).
#include <catch2/catch.hpp>
#include <fluid/gl/renderer.h>

#include <algorithm>
#include <string>

using namespace fluid::gl;

TEST_CASE("Embedded shaders: sorted names, #version 330 core, lookup", "[gl][shaders]") {
    const auto names = shaderNames();
    REQUIRE(names.size() >= 10);
    CHECK(std::is_sorted(names.begin(), names.end()));
    CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
    for (const std::string_view name : names) {
        INFO(std::string(name));
        const std::string_view source = shaderSource(name);
        REQUIRE(!source.empty());
        CHECK(source.substr(0, 18) == "#version 330 core\n");
        CHECK(source.find("void main()") != std::string_view::npos);
        const bool stage = name.ends_with(".vert") || name.ends_with(".frag");
        CHECK(stage);
    }
    // The programs the renderer links exist.
    for (const char* name : {"shape.vert", "shape.frag", "fullscreen.vert", "metaball_field.vert",
                             "metaball_field.frag", "metaball_composite.frag",
                             "pressure_square.vert", "pressure_square.frag", "particle_disc.vert",
                             "particle_disc.frag", "solid_mask.frag", "solid_distance.frag"}) {
        INFO(name);
        CHECK(!shaderSource(name).empty());
    }
    CHECK(shaderSource("missing.frag").empty());
    CHECK(shaderSource("").empty());
    CHECK(shaderSource("shape").empty());
}

TEST_CASE("defaultColour: water blue, yoghurt cream, a fixed palette otherwise", "[gl][styles]") {
    const glm::vec3 water = defaultColour("water", 0);
    CHECK(water.b > water.g);
    CHECK(water.g > water.r);
    CHECK(water.b > 0.8f);
    const glm::vec3 yoghurt = defaultColour("yoghurt", 1);
    CHECK(yoghurt.r > 0.9f);
    CHECK(yoghurt.g > 0.85f);
    CHECK(yoghurt.b > 0.7f);
    CHECK(yoghurt.b < yoghurt.r); // cream, not white-blue
    // The name decides, not the index.
    CHECK(defaultColour("water", 5) == water);
    // Other names: deterministic by index, different neighbours, never water's colour.
    const glm::vec3 a = defaultColour("honey", 2);
    CHECK(defaultColour("oil", 2) == a);
    CHECK(defaultColour("honey", 3) != a);
    for (uint32_t i = 0; i < 32; ++i) {
        const glm::vec3 c = defaultColour("slime", i);
        CHECK(c != water);
        CHECK(c != yoghurt);
        CHECK(c.r >= 0.0f);
        CHECK(c.r <= 1.0f);
    }
}

TEST_CASE("viewName and RenderSettings defaults", "[gl][styles]") {
    CHECK(viewName(View::Metaballs) == "metaballs");
    CHECK(viewName(View::Pressure) == "pressure");
    CHECK(viewName(View::Particles) == "particles");
    const RenderSettings settings;
    CHECK(settings.view == View::Metaballs);
    CHECK(settings.threshold == 0.6f);
    CHECK(settings.pressureScale == 0.0f);
}
