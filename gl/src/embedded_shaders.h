// fluid::gl internals — the shader table cmake/embed_shaders.cmake generates at build time.
#pragma once
#include <cstddef>
#include <string_view>

namespace fluid::gl::detail {

/// Number of embedded shaders.
extern const std::size_t kShaderCount;
/// File names of the shaders, sorted (std::string_view ordering).
extern const std::string_view kShaderNames[];
/// Source text of each shader, in the order of `kShaderNames`.
extern const std::string_view kShaderSources[];

} // namespace fluid::gl::detail
