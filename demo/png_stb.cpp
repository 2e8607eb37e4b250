// fluid-demo — writePng (platform.h) with stb_image_write, for platforms without an image
// library of their own (the GLFW layer; Debian's libstb-dev).
#include "demo/platform.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace fluid::demo {

bool writePng(const std::string& path, glm::ivec2 size, const std::vector<uint8_t>& rgba) {
    if (size.x <= 0 || size.y <= 0 || rgba.size() < size_t(size.x) * size_t(size.y) * 4) {
        return false;
    }
    return stbi_write_png(path.c_str(), size.x, size.y, 4, rgba.data(), size.x * 4) != 0;
}

} // namespace fluid::demo
