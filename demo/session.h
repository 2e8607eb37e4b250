// fluid-demo — one level being played: the level, the plugins the game drives (pointer,
// gravity), the two materials the player can drop, and what the renderer needs to draw it.
// Shared by the interactive game and the headless runner.
#pragma once
#include "demo/level_list.h"
#include "demo/scene_draw.h"

#include <fluid/gl/renderer.h>
#include <fluid/level.h>
#include <fluid/plugins/pointer.h>
#include <fluid/registry.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace fluid::demo {

/// A loaded level plus the game's additions. Main thread only (it owns the Box2D world).
class Session {
public:
    /// Loads `file` with `workers` worker threads (unit: count; >= 1). Adds what the controls
    /// need and the file may lack: a `force.pointer`, a `force.gravity` (zero when the level
    /// has none, so G can switch it on), and water and yoghurt materials at the level's
    /// particle spacing (so M and Space work everywhere). Throws `fluid::LevelError` or
    /// `fluid::Error` as `loadLevel`.
    Session(const LevelFile& file, uint32_t workers);

    /// The level being played.
    Level& level() { return m_level; }
    /// See above.
    const Level& level() const { return m_level; }
    /// The file it came from.
    const LevelFile& file() const { return m_file; }
    /// The rectangle the camera frames (fixed at load).
    const ViewBounds& bounds() const { return m_bounds; }
    /// How the renderer draws each material index.
    const std::vector<gl::MaterialStyle>& styles() const { return m_styles; }
    /// The camera that frames the level in a target of `size` (unit: px) below the band the
    /// HUD and the level banner keep to (`frameLevel`, demo/layout.h).
    gl::Camera camera(glm::ivec2 size) const;
    /// A line about 1.5 px wide at the camera's zoom (unit: m).
    float lineWidth(const gl::Camera& camera) const;

    /// Steps one frame (1 / frameRate s) and measures it. Throws as `Level::step`.
    void step();
    /// Steps a frame of `frameDt` s (the display's frame time; the world carries what is not a
    /// whole sub-step and the renderer draws between sub-steps). Throws as `Level::step`.
    void stepFor(float frameDt);
    /// Wall time of the last step (unit: ms).
    double lastStepMs() const { return m_lastStepMs; }

    /// Moves the pointer (unit: m) and sets how hard it pushes: `push` > 0 pushes, < 0 pulls,
    /// 0 off (unit: 1; [-1, 1]).
    void setPointer(glm::vec2 position, float push);
    /// Reach of the pointer (unit: m).
    float pointerRadius() const { return m_pointerRadius; }

    /// True when uniform gravity is on.
    bool gravityOn() const;
    /// Switches uniform gravity between the level's own (or (0, -9.81) m/s^2 when the level
    /// has none) and zero, in the fluid and in Box2D.
    void toggleGravity();

    /// The material Space drops: 0 water, 1 yoghurt.
    uint32_t dropMaterial() const { return m_drop; }
    /// Name of the material Space drops.
    const std::string& dropMaterialName() const;
    /// Switches the dropped material between water and yoghurt.
    void cycleDropMaterial() { m_drop = 1 - m_drop; }
    /// Drops a round blob of the current material at `center` (unit: m). Returns the number of
    /// particles added; throws `fluid::Error` when the world is full.
    uint32_t dropBlob(glm::vec2 center);
    /// Drops a 0.1 m crate at `center` (unit: m) into a level with Box2D bodies; the density
    /// cycles through 0.5, 0.8 and 1.6 times water's. Returns false in a level without bodies.
    bool dropCrate(glm::vec2 center);

    /// Saves the level as it stands (`Level::saveFile`: liquid, Box2D bodies, coupling) to
    /// `path`. Throws `fluid::Error` naming the file.
    void save(const std::string& path) const;
    /// Goes back to a save made by `save` for this level (the same level text, wherever its
    /// file was: a desktop's save loads in the page and back): the liquid, the bodies and the
    /// gravity switch as they were (the material Space drops stays as chosen). Throws
    /// `fluid::Error` for a bad save or one of another level (this session is unchanged then).
    void restore(const std::string& path);

    /// Fills `under` and `over` with the level's walls, sensors, bodies and nozzles, and the
    /// pointer ring when `showPointer`.
    /// The bodies are drawn `factor` (unit: 1; [0, 1]) of the way from their pose at the start
    /// of the last level frame to their current one, as the liquid (1: current).
    void drawShapes(const gl::Camera& camera, bool showPointer, gl::ShapeBatch& under,
                    gl::ShapeBatch& over, float factor = 1.0f) const;

private:
    LevelFile m_file;
    uint32_t m_workers = 1;
    Registry m_registry;
    Level m_level;
    std::vector<BodyPose> m_previousPoses; // the bodies at the start of the last level frame
    ViewBounds m_bounds;
    std::vector<gl::MaterialStyle> m_styles;
    PointerForce* m_pointer = nullptr;
    Plugin* m_gravity = nullptr;
    glm::vec2 m_gravityOn{0.0f, -9.81f};
    glm::vec2 m_pointerPos{0.0f, 0.0f};
    float m_pointerPush = 0.0f;
    float m_pointerRadius = 0.1f;
    MaterialId m_materials[2]{};
    std::string m_materialNames[2]{"water", "yoghurt"};
    uint32_t m_drop = 0;
    uint32_t m_dropped = 0; // blobs dropped (the next colour, in levels that mix colours)
    uint32_t m_crates = 0;
    double m_lastStepMs = 0.0;
};

} // namespace fluid::demo
