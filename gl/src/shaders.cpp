// fluid::gl — lookup in the shader table embedded at build time.
#include "embedded_shaders.h"

#include <fluid/gl/renderer.h>

#include <algorithm>

namespace fluid::gl {

std::string_view shaderSource(std::string_view name) {
    const std::string_view* first = detail::kShaderNames;
    const std::string_view* last = first + detail::kShaderCount;
    // The generator sorts the table, so a binary search finds the name.
    const std::string_view* it = std::lower_bound(first, last, name);
    if (it == last || *it != name) {
        return {};
    }
    return detail::kShaderSources[it - first];
}

std::span<const std::string_view> shaderNames() {
    return {detail::kShaderNames, detail::kShaderCount};
}

} // namespace fluid::gl
