// fluid-demo — grabbing a body (see grab.h).
#include "demo/grab.h"

namespace fluid::demo {

b2Body* bodyAt(b2World& world, glm::vec2 p) {
    struct Query final : b2QueryCallback {
        b2Vec2 point;
        b2Body* found = nullptr;
        bool ReportFixture(b2Fixture* fixture) override {
            b2Body* body = fixture->GetBody();
            if (body->GetType() != b2_staticBody && fixture->TestPoint(point)) {
                found = body;
                return false;
            }
            return true;
        }
    } query;
    query.point = {p.x, p.y};
    b2AABB box;
    box.lowerBound = {p.x - 1e-3f, p.y - 1e-3f};
    box.upperBound = {p.x + 1e-3f, p.y + 1e-3f};
    world.QueryAABB(&query, box);
    return query.found;
}

void Grab::begin(b2World& world, b2Body* target, glm::vec2 p) {
    body = target;
    localPoint = body->GetLocalPoint({p.x, p.y});
    if (body->GetType() == b2_dynamicBody) {
        b2BodyDef groundDef;
        ground = world.CreateBody(&groundDef);
        b2MouseJointDef def;
        def.bodyA = ground;
        def.bodyB = body;
        def.target = {p.x, p.y};
        def.maxForce = 300.0f * body->GetMass();
        b2LinearStiffness(def.stiffness, def.damping, 5.0f, 0.7f, def.bodyA, def.bodyB);
        joint = static_cast<b2MouseJoint*>(world.CreateJoint(&def));
    }
    body->SetAwake(true);
}
void Grab::update(glm::vec2 p, float dt) {
    if (body == nullptr) {
        return;
    }
    if (joint != nullptr) {
        joint->SetTarget({p.x, p.y});
        return;
    }
    const b2Vec2 at = body->GetWorldPoint(localPoint);
    b2Vec2 v{(p.x - at.x) / dt, (p.y - at.y) / dt};
    const float speed = v.Length();
    constexpr float kMaxSpeed = 3.0f; // m/s: fast enough to follow, slow enough not to splash
    if (speed > kMaxSpeed) {
        v *= kMaxSpeed / speed;
    }
    body->SetLinearVelocity(v);
    body->SetAngularVelocity(spin);
}
void Grab::end(b2World* world) {
    if (body != nullptr && body->GetType() == b2_kinematicBody) {
        body->SetLinearVelocity({0.0f, 0.0f});
        body->SetAngularVelocity(0.0f);
    }
    if (world != nullptr && ground != nullptr) {
        world->DestroyBody(ground); // destroys the joint too
    }
    *this = Grab{};
}

} // namespace fluid::demo
