// fluid-demo — context settings and overlay glue.
#include <GL/glew.h> // before any other GL header

#include "demo/overlay.h"

#include <fluid/error.h>

#include <SFML/Graphics/Image.hpp>

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

HudInfo hudFor(const Session& session, gl::View view) {
    const Level& level = session.level();
    HudInfo hud{};
    hud.particles = level.world.particleCount();
    hud.simMsPerFrame = float(session.lastStepMs());
    hud.substeps =
        level.coupling ? level.coupling->profile().substeps : level.world.profile().substeps;
    hud.view = gl::viewName(view);
    hud.material = session.dropMaterialName();
    hud.zeroG = !session.gravityOn();
    return hud;
}

bool savePng(const gl::Renderer& renderer, const std::string& path) {
    std::vector<uint8_t> rgba;
    renderer.readPixels(rgba);
    const glm::ivec2 size = renderer.size();
    sf::Image image;
    image.create(unsigned(size.x), unsigned(size.y), rgba.data());
    return image.saveToFile(path);
}

} // namespace fluid::demo
