// floating_crates: a Box2D world coupled to the fluid — a tank of water, a crate and a ball
// that float, and a stone that sinks. Prints where each body settles and how deep it floats.
#include <fluid/box2d/coupling.h>
#include <fluid/fluid.h>

#include <box2d/box2d.h>

#include <cstdio>
#include <memory>

int main() {
    // The fluid: a 1.2 m wide tank holding 0.4 m of water, gravity as a force plugin.
    fluid::World world(fluid::WorldDef{});
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<fluid::GravityForce>(0.0f, -9.81f));
    world.addBoundary(std::make_unique<fluid::BoxContainer>(0.0f, 0.0f, 1.2f, 1.0f));
    fluid::BlobDef pool;
    pool.material = water;
    pool.shape = fluid::Shape::box({0.005f, 0.0f}, {1.195f, 0.4f});
    world.spawnBlob(pool);

    // The rigid bodies: the same gravity, a floor for the stone to rest on. The floor and
    // walls of the fluid's tank (boundary.box) do not stop Box2D bodies; the b2 floor does.
    b2World physics(b2Vec2(0.0f, -9.81f));
    b2BodyDef floorDef;
    b2Body* floor = physics.CreateBody(&floorDef);
    b2PolygonShape floorShape;
    floorShape.SetAsBox(0.6f, 0.05f, b2Vec2(0.6f, -0.05f), 0.0f);
    floor->CreateFixture(&floorShape, 0.0f);

    // Densities relative to water's areal density (kg/m^2): 0.5 floats half under.
    const float rho = fluid::box2d::arealDensity(world, water);
    struct Crate {
        const char* name;
        float x, ratio;
        bool round;
    };
    const Crate crates[] = {
        {"crate", 0.25f, 0.5f, false}, {"ball", 0.6f, 0.3f, true}, {"stone", 0.95f, 2.0f, false}};
    b2Body* bodies[3];
    for (int k = 0; k < 3; ++k) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position.Set(crates[k].x, 0.55f);
        bodies[k] = physics.CreateBody(&def);
        b2PolygonShape box;
        box.SetAsBox(0.06f, 0.06f);
        b2CircleShape disc;
        disc.m_radius = 0.06f;
        b2FixtureDef fixture;
        fixture.shape = crates[k].round ? static_cast<b2Shape*>(&disc) : &box;
        fixture.density = crates[k].ratio * rho;
        fixture.friction = 0.4f;
        bodies[k]->CreateFixture(&fixture);
    }

    // The coupling: every fixture becomes a boundary (a solid; the tank, a container, projects
    // after the solids whatever the order they were added in).
    fluid::box2d::Coupling coupling(world, physics);
    for (int frame = 0; frame < 300; ++frame) {
        coupling.step(world, 1.0f / 60.0f); // per sub-step: Box2D, fluid, forces to bodies
        for (const fluid::box2d::SplashEvent& splash : coupling.splashes()) {
            std::printf("splash at (%.2f, %.2f), %.2f m/s\n", splash.position.x, splash.position.y,
                        splash.speed);
        }
    }
    for (int k = 0; k < 3; ++k) {
        const fluid::box2d::BodyReport* report = coupling.report(bodies[k]);
        std::printf("%-5s density %.2f x water: y = %.3f m, submerged %.0f%%, fluid force %.1f N\n",
                    crates[k].name, crates[k].ratio, bodies[k]->GetPosition().y,
                    report != nullptr ? 100.0f * report->submergedFraction : 0.0f,
                    report != nullptr ? report->force.y : 0.0f);
    }
    return 0;
}
