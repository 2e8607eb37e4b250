// fluid-demo — the liquid under the cursor (fluid::sample) for the HUD, and the laser (L): a ray
// cast from the cursor, drawn to where it meets the liquid with the surface's normal there.
#pragma once
#include <fluid/gl/shapes.h>
#include <fluid/query.h>
#include <fluid/world.h>

#include <glm/vec2.hpp>

#include <string>

namespace fluid::demo {

/// Reads the liquid at the cursor each frame, and casts the laser while it is on. Main thread,
/// between steps.
class LiquidProbe {
public:
    /// Where the laser points from the cursor: down and to the right, 60 degrees below the
    /// horizontal, so it meets a pool from above and shows the normal apart from the beam.
    static constexpr glm::vec2 kDirection{0.5f, -0.8660254f};
    /// How far it reaches (unit: m): across any shipped level.
    static constexpr float kReach = 8.0f;

    /// Turns the laser on or off (the L key).
    void toggleLaser() { m_laserOn = !m_laserOn; }
    bool laserOn() const { return m_laserOn; }

    /// Samples the liquid at `cursor` (unit: m) and, with the laser on, casts it from there.
    void update(const World& world, glm::vec2 cursor);

    /// The HUD's line for the cursor: "water, 4.2 cm deep, 412 Pa, 0.31 m/s" or "air".
    const std::string& cursorText() const { return m_cursorText; }
    /// The HUD's line for the laser ("" while off): "hits water at (0.41, 0.22) m, 0.27 m away".
    const std::string& laserText() const { return m_laserText; }

    /// The beam (red, to the hit or its full reach), the hit (a ring) and the normal (yellow,
    /// `normalLength` m long), `lineWidth` m wide. Nothing while the laser is off.
    void draw(float lineWidth, float normalLength, gl::ShapeBatch& batch) const;

    /// The script summary's fields: " probe=in|out probe_depth=D laser=X,Y laser_normal=NX,NY"
    /// (laser=miss when it meets no liquid; the laser fields only while it is on).
    std::string summary() const;

private:
    bool m_laserOn = false;
    glm::vec2 m_cursor{0.0f, 0.0f};
    LiquidSample m_sample;
    RayHit m_hit;
    std::string m_cursorText, m_laserText;
};

} // namespace fluid::demo
