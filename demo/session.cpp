// fluid-demo — a level being played.
#include "demo/session.h"

#include "demo/layout.h"


#include <fluid/box2d/coupling.h>
#include <fluid/groups.h>
#include <fluid/plugins/builtin.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace fluid::demo {
namespace {

// A preset scaled to another lattice spacing: mass with the particle's area, the smoothing
// distance with the spacing, so a blob dropped into a level of coarse water
// has the level's resolution.
Material atSpacing(Material material, float spacing, float depth) {
    const float own = particleSpacing(material, depth);
    const float s = spacing / own;
    material.mass *= s * s;
    material.smoothingDistance *= s;
    return material;
}

LevelOptions optionsFor(uint32_t workers) {
    LevelOptions options;
    options.workerCount = std::max(workers, 1u);
    return options;
}

} // namespace

Session::Session(const LevelFile& file, uint32_t workers)
    : m_file(file), m_workers(std::max(workers, 1u)) {
    registerBuiltinPlugins(m_registry);
    m_level = loadLevel(file.path, m_registry, optionsFor(workers));
    World& world = m_level.world;
    // Drawn between the last two level frames (fluid/groups.h, Interpolation::Step): the game
    // steps fixed frames from its frame pacer and draws at the fraction of a frame the pacer
    // holds, smooth at any display rate.
    setInterpolation(world, Interpolation::Step);

    // The bounds come first: they frame the particles as the file placed them.
    m_bounds = levelBounds(m_level);
    const glm::vec2 size = m_bounds.hi - m_bounds.lo;
    m_pointerRadius = 0.12f * std::max(size.x, size.y);

    // Water and yoghurt, found by name or added at the level's spacing.
    const float depth = world.def().depth;
    const float spacing = world.materialCount() > 0
                              ? particleSpacing(world.material(MaterialId{0}), depth)
                              : particleSpacing(water(), depth);
    bool found[2] = {false, false};
    for (uint32_t i = 0; i < world.materialCount(); ++i) {
        for (uint32_t k = 0; k < 2; ++k) {
            if (!found[k] && world.material(MaterialId{uint16_t(i)}).name == m_materialNames[k]) {
                m_materials[k] = MaterialId{uint16_t(i)};
                found[k] = true;
            }
        }
    }
    for (uint32_t k = 0; k < 2; ++k) {
        if (!found[k]) {
            Material m = atSpacing(k == 0 ? water() : yoghurt(), spacing, depth);
            m.name = m_materialNames[k];
            m_materials[k] = world.addMaterial(m);
        }
    }
    for (uint32_t i = 0; i < world.materialCount(); ++i) {
        const Material& m = world.material(MaterialId{uint16_t(i)});
        m_styles.push_back({gl::defaultColour(m.name, i), particleSpacing(m, depth)});
    }

    // The uniform gravity G switches: the level's, else a new zero one.
    for (const auto& force : world.forces()) {
        if (force->type() == "force.gravity") {
            m_gravity = force.get();
            break;
        }
    }
    if (m_gravity == nullptr) {
        const std::array<ParamValue, 2> zero{{{"gx", 0.0}, {"gy", 0.0}}};
        m_gravity = &world.addForce(m_registry.createForce("force.gravity", zero));
    } else {
        const glm::vec2 g{float(m_gravity->param("gx")), float(m_gravity->param("gy"))};
        if (g != glm::vec2(0.0f)) {
            m_gravityOn = g;
        }
    }

    // The mouse.
    const std::array<ParamValue, 2> pointer{
        {{"radius", double(m_pointerRadius)}, {"strength", 40.0}}};
    m_pointer = &static_cast<PointerForce&>(
        world.addForce(m_registry.createForce(PointerForce::kType, pointer)));
}

namespace {

// The session's pointer and gravity plugins among a world's forces: the last pointer (the
// session adds its own last), the first gravity (the level's, or the session's zero one).
std::pair<PointerForce*, Plugin*> findControls(World& world) {
    PointerForce* pointer = nullptr;
    Plugin* gravity = nullptr;
    for (const auto& force : world.forces()) {
        if (gravity == nullptr && force->type() == "force.gravity") {
            gravity = force.get();
        }
        if (auto* p = dynamic_cast<PointerForce*>(force.get())) {
            pointer = p;
        }
    }
    return {pointer, gravity};
}

} // namespace

void Session::save(const std::string& path) const {
    m_level.saveFile(path);
}

void Session::restore(const std::string& path) {
    Level restored = loadLevelSave(path, m_registry, optionsFor(m_workers));
    // The same level is the same text wherever its file lies: a save made on the desktop
    // loads in the browser's page, whose levels sit in another folder, and back.
    if (restored.source != m_level.source) {
        throw Error("'" + path + "' is a save of '" + restored.file + "', whose text is not '" +
                    m_level.file + "''s");
    }
    // The session's own materials and plugins were in the world when it was saved (plugins
    // live on the heap: the pointers outlive the level's move).
    const auto [pointer, gravity] = findControls(restored.world);
    if (pointer == nullptr || gravity == nullptr) {
        throw Error("'" + path + "' lacks the demo's gravity or pointer plugin");
    }
    m_level = std::move(restored);
    m_pointer = pointer;
    m_gravity = gravity;
}

gl::Camera Session::camera(glm::ivec2 size) const {
    // Below the band the HUD and the banner keep to (demo/layout.h).
    return frameLevel(m_bounds.lo, m_bounds.hi, size);
}

float Session::lineWidth(const gl::Camera& camera) const {
    return 1.5f / std::max(camera.pixelsPerMetre, 1e-6f);
}

void Session::step() {
    stepFor(1.0f / m_level.frameRate);
}

void Session::stepFor(float frameDt) {
    m_pointer->setPointer(m_pointerPos, std::abs(m_pointerPush));
    m_pointer->setParam("strength", m_pointerPush < 0.0f ? -40.0 : 40.0);
    m_previousPoses.clear();
    if (m_level.physics) {
        for (const b2Body* b = m_level.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
            m_previousPoses.push_back({b, {b->GetPosition().x, b->GetPosition().y}, b->GetAngle()});
        }
    }
    const auto start = std::chrono::steady_clock::now();
    m_level.step(frameDt);
    const auto end = std::chrono::steady_clock::now();
    m_lastStepMs = std::chrono::duration<double, std::milli>(end - start).count();
}

void Session::setPointer(glm::vec2 position, float push) {
    m_pointerPos = position;
    m_pointerPush = std::clamp(push, -1.0f, 1.0f);
}

bool Session::gravityOn() const {
    return m_gravity->param("gx") != 0.0 || m_gravity->param("gy") != 0.0;
}

void Session::toggleGravity() {
    const glm::vec2 g = gravityOn() ? glm::vec2(0.0f) : m_gravityOn;
    m_gravity->setParam("gx", g.x);
    m_gravity->setParam("gy", g.y);
    if (m_level.physics) {
        // The coupling's hydrostatic buoyancy reads Box2D's gravity: keep the two the same.
        m_level.physics->SetGravity({g.x, g.y});
        for (b2Body* body = m_level.physics->GetBodyList(); body; body = body->GetNext()) {
            body->SetAwake(true);
        }
    }
}

const std::string& Session::dropMaterialName() const {
    return m_materialNames[m_drop];
}

uint32_t Session::dropBlob(glm::vec2 center) {
    BlobDef blob;
    const float extent = std::max(m_bounds.hi.x - m_bounds.lo.x, m_bounds.hi.y - m_bounds.lo.y);
    blob.shape = Shape::circle(center, std::clamp(0.05f * extent, 0.02f, 0.08f));
    blob.material = m_materials[m_drop];
    World& world = m_level.world;
    if (colourMixing(world) > 0.0f) {
        // A level that mixes colours: each blob dropped is a group of a colour of its own.
        static constexpr Colour kPalette[] = {{230, 60, 200, 255}, {40, 200, 90, 255},
                                              {250, 140, 20, 255}, {30, 200, 230, 255},
                                              {240, 240, 240, 255}, {120, 60, 230, 255}};
        const Colour colour = kPalette[m_dropped++ % std::size(kPalette)];
        const uint32_t before = world.particleCount();
        spawnGroup(world, blob, GroupDef{0, colour});
        return world.particleCount() - before;
    }
    return world.spawnBlob(blob);
}

bool Session::dropCrate(glm::vec2 center) {
    if (!m_level.physics) {
        return false;
    }
    constexpr std::array<float, 3> kRatios{0.5f, 0.8f, 1.6f};
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position = {center.x, center.y};
    def.angle = 0.3f * float(m_crates % 3) - 0.3f;
    b2Body* body = m_level.physics->CreateBody(&def);
    m_previousPoses.clear(); // a new body may sit where a destroyed one's pose is kept
    b2PolygonShape box;
    box.SetAsBox(0.05f, 0.05f);
    b2FixtureDef fixture;
    fixture.shape = &box;
    fixture.density =
        kRatios[m_crates % kRatios.size()] * box2d::arealDensity(m_level.world, m_materials[0]);
    fixture.friction = 0.4f;
    body->CreateFixture(&fixture);
    ++m_crates;
    return true;
}

void Session::drawShapes(const gl::Camera& camera, bool showPointer, gl::ShapeBatch& under,
                         gl::ShapeBatch& over, float factor) const {
    under.clear();
    over.clear();
    const double fill = m_level.goal.present && m_level.goal.amount > 0.0
                            ? m_level.goalValue() / m_level.goal.amount
                            : 0.0;
    // Walls and sensors are outlined at 0.4% of the level's size (the bounds fixed at load).
    const glm::vec2 size = m_bounds.hi - m_bounds.lo;
    drawUnder(m_level, fill, 0.004f * std::max(size.x, size.y), under);
    const float width = lineWidth(camera);
    drawOver(m_level, width, over, m_previousPoses, factor);
    if (showPointer) {
        const glm::vec4 colour = m_pointerPush > 0.0f   ? glm::vec4(1.0f, 0.55f, 0.3f, 0.8f)
                                 : m_pointerPush < 0.0f ? glm::vec4(0.4f, 0.8f, 1.0f, 0.8f)
                                                        : glm::vec4(1.0f, 1.0f, 1.0f, 0.35f);
        over.ring(m_pointerPos, m_pointerRadius, 1.5f * width, colour);
    }
}

} // namespace fluid::demo
