// fluid-demo — context settings and overlay glue.
#include <GL/glew.h> // before any other GL header

#include "demo/overlay.h"

#include <fluid/error.h>

#include <string>

namespace fluid::demo {

sf::ContextSettings glContextSettings() {
    return sf::ContextSettings(24, 8, 0, 3, 3, sf::ContextSettings::Core);
}

void checkContext(const sf::Window& window) {
    const sf::ContextSettings got = window.getSettings();
    const bool core = (got.attributeFlags & sf::ContextSettings::Core) != 0;
    if (got.majorVersion * 10 + got.minorVersion < 33 || !core) {
        throw Error("needs an OpenGL 3.3 core context, but the driver gave OpenGL " +
                    std::to_string(got.majorVersion) + "." + std::to_string(got.minorVersion) +
                    (core ? " core" : " compatibility") +
                    " (software rendering: Mesa's llvmpipe provides 3.3 core, e.g. under Xvfb)");
    }
}

void beginOverlay(const gl::Renderer& renderer) {
    glBindFramebuffer(GL_FRAMEBUFFER, renderer.framebuffer());
    glViewport(0, 0, renderer.size().x, renderer.size().y);
}

BannerInfo bannerFor(const Level& level) {
    BannerInfo banner{};
    banner.name = level.name;
    banner.text = level.goal.present && !level.goal.description.empty() ? level.goal.description
                                                                        : level.description;
    banner.state = level.goalState();
    banner.goalValue = level.goalValue();
    banner.goalAmount = level.goal.amount;
    banner.measure = level.goal.measure;
    banner.time = level.world.time();
    banner.timeLimit = level.goal.timeLimit;
    return banner;
}

} // namespace fluid::demo
