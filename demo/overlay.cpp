// fluid-demo — overlay glue.
#if defined(FLUID_GL_ES) // fluid::gl's GL: OpenGL ES 3.0 / WebGL2, or 3.3 core through GLEW
#include <GLES3/gl3.h>
#else
#include <GL/glew.h> // before any other GL header
#endif

#include "demo/overlay.h"
#include "demo/platform.h"

#include <fluid/error.h>

#include <string>

namespace fluid::demo {

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
    return writePng(path, renderer.size(), rgba);
}

} // namespace fluid::demo
