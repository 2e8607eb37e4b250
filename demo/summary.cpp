// fluid-demo — the scripted run's summary line (see summary.h).
#include "demo/summary.h"

#include <fluid/internal/binary.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <cstdio>
#include <span>
#include <vector>

namespace fluid::demo {

uint64_t stateHash(const Level& level) {
    std::vector<float> state;
    const World& world = level.world;
    for (const auto& channel :
         {world.positionX(), world.positionY(), world.velocityX(), world.velocityY()}) {
        state.insert(state.end(), channel.begin(), channel.end());
    }
    for (const auto& entry : level.bodies) {
        const b2Body* body = entry.second;
        state.insert(state.end(),
                     {body->GetPosition().x, body->GetPosition().y, body->GetAngle(),
                      body->GetLinearVelocity().x, body->GetLinearVelocity().y,
                      body->GetAngularVelocity()});
    }
    return internal::fnv1a(std::as_bytes(std::span<const float>(state)));
}

std::string summaryLine(const Session& session, const SummaryInfo& info) {
    const Level& level = session.level();
    const World& world = level.world;
    std::string line = "level=" + session.file().stem;
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, " frames=%u time=%.9g particles=%u", info.frames,
                  world.time(), world.particleCount());
    line += buffer;
    const auto x = world.positionX(), y = world.positionY();
    const auto material = world.materialIndex();
    std::vector<uint32_t> counts(world.materialCount(), 0);
    double cx = 0.0, cy = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        ++counts[material[i]];
        cx += x[i];
        cy += y[i];
    }
    for (uint32_t m = 0; m < world.materialCount(); ++m) {
        line += " m_" + world.material(MaterialId{uint16_t(m)}).name + "=" +
                std::to_string(counts[m]);
    }
    const double n = std::max<double>(1.0, double(x.size()));
    std::snprintf(buffer, sizeof buffer, " cx=%.4f cy=%.4f", cx / n, cy / n);
    line += buffer;
    line += " view=" + std::string(info.view);
    line += std::string(" gravity=") + (session.gravityOn() ? "on" : "off");
    line += " material=" + session.dropMaterialName();
    line += std::string(" paused=") + (info.paused ? "1" : "0");
    line += " bodies=" + std::to_string(level.physics ? level.physics->GetBodyCount() : 0);
    constexpr const char* kGoal[] = {"none", "pending", "won", "lost"};
    std::snprintf(buffer, sizeof buffer, " goal=%s goal_value=%.4f",
                  kGoal[int(level.goalState())], level.goalValue());
    line += buffer;
    for (const auto& [name, body] : level.bodies) {
        std::snprintf(buffer, sizeof buffer, " b_%s=%.4f,%.4f", name.c_str(),
                      double(body->GetPosition().x), double(body->GetPosition().y));
        line += buffer;
    }
    line += info.probe;
    std::snprintf(buffer, sizeof buffer, " hash=%016llx",
                  static_cast<unsigned long long>(stateHash(level)));
    line += buffer;
    return line;
}

} // namespace fluid::demo
