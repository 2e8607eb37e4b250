// fluid-demo — the liquid under the cursor and the laser (probe.h).
#include "demo/probe.h"

#include <glm/geometric.hpp>

#include <cstdio>

namespace fluid::demo {

namespace {

std::string materialName(const World& world, MaterialId id) {
    return id.index < world.materialCount() ? world.material(id).name : std::string("liquid");
}

} // namespace

void LiquidProbe::update(const World& world, glm::vec2 cursor) {
    m_cursor = cursor;
    m_sample = sample(world, cursor);
    char text[160];
    if (m_sample.inLiquid) {
        std::snprintf(text, sizeof text, "%s, %.1f cm deep, %.0f Pa, %.2f m/s",
                      materialName(world, m_sample.material).c_str(),
                      double(100.0f * m_sample.depth), double(m_sample.pressure),
                      double(glm::length(m_sample.velocity)));
        m_cursorText = text;
    } else {
        m_cursorText = "air";
    }
    m_laserText.clear();
    m_hit = RayHit{};
    if (!m_laserOn) {
        return;
    }
    m_hit = rayCast(world, cursor, cursor + kReach * kDirection);
    if (!m_hit.hit) {
        m_laserText = "misses the liquid";
    } else if (m_hit.startsInside) {
        m_laserText = "starts in the " + materialName(world, m_hit.material);
    } else {
        std::snprintf(text, sizeof text, "hits %s at (%.2f, %.2f) m, %.2f m away",
                      materialName(world, m_hit.material).c_str(), double(m_hit.point.x),
                      double(m_hit.point.y), double(m_hit.fraction * kReach));
        m_laserText = text;
    }
}

void LiquidProbe::draw(float lineWidth, float normalLength, gl::ShapeBatch& batch) const {
    if (!m_laserOn) {
        return;
    }
    const glm::vec4 beam{1.0f, 0.15f, 0.1f, 0.9f}, normal{1.0f, 0.85f, 0.1f, 1.0f};
    const glm::vec2 end = m_hit.hit ? m_hit.point : m_cursor + kReach * kDirection;
    batch.line(m_cursor, end, lineWidth, beam);
    batch.disc(m_cursor, 1.5f * lineWidth, beam);
    if (m_hit.hit && !m_hit.startsInside) {
        batch.ring(m_hit.point, 3.0f * lineWidth, lineWidth, normal);
        batch.line(m_hit.point, m_hit.point + normalLength * m_hit.normal, lineWidth, normal);
    }
}

std::string LiquidProbe::summary() const {
    char text[200];
    std::snprintf(text, sizeof text, " probe=%s probe_depth=%.4f", m_sample.inLiquid ? "in" : "out",
                  double(m_sample.depth));
    std::string out = text;
    if (m_laserOn) {
        if (m_hit.hit) {
            std::snprintf(text, sizeof text, " laser=%.4f,%.4f laser_normal=%.3f,%.3f",
                          double(m_hit.point.x), double(m_hit.point.y), double(m_hit.normal.x),
                          double(m_hit.normal.y));
            out += text;
        } else {
            out += " laser=miss";
        }
    }
    return out;
}

} // namespace fluid::demo
