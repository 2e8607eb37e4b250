// fluid::gl — view names and default material colours (no GL).
#include <fluid/gl/renderer.h>

#include <array>

namespace fluid::gl {

std::string_view viewName(View view) {
    const std::string_view name = nameIn(kViewNames, view);
    return name.empty() ? "unknown" : name;
}

glm::vec3 defaultColour(std::string_view materialName, uint32_t index) {
    if (materialName == "water") {
        return {0.15f, 0.45f, 0.95f};
    }
    if (materialName == "yoghurt") {
        return {0.96f, 0.93f, 0.82f};
    }
    // Distinct from the water blue, the yoghurt cream and each other on a dark background.
    static constexpr std::array<glm::vec3, 8> kPalette{{
        {0.95f, 0.55f, 0.15f}, // orange
        {0.35f, 0.80f, 0.35f}, // green
        {0.70f, 0.40f, 0.90f}, // violet
        {0.90f, 0.25f, 0.30f}, // red
        {0.20f, 0.80f, 0.75f}, // teal
        {0.95f, 0.85f, 0.25f}, // yellow
        {0.95f, 0.50f, 0.70f}, // pink
        {0.60f, 0.45f, 0.30f}, // brown
    }};
    return kPalette[index % kPalette.size()];
}

} // namespace fluid::gl
