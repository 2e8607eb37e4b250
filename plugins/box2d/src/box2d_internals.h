// fluid::box2d internals — the members of Box2D 2.4.1 that a save must carry for a restored
// world to continue bit-identically, and that Box2D keeps private: contacts (their manifolds and
// warm-starting impulses, flags, friction mixing, TOI state), the broad phase's dynamic tree and
// move buffer, bodies' sweeps, centroidal inertia, forces and sleep timers, revolute joints'
// impulses, the world's last inverse time step. physics_save.cpp only.
//
// Reached by the standard's one access-free path: an explicit instantiation may name private
// members ([temp.spec.general]/6), and `Expose` hands the member pointer out through a friend
// function. The layout is Box2D 2.4.1's, as Debian ships it (libbox2d-dev 2.4.1) and the web
// build compiles it; b2_version 2.4.0 is what 2.4.1 reports.
#pragma once

#include <box2d/box2d.h>

namespace fluid::box2d::detail {

template <class Tag, typename Tag::type Member> struct Expose {
    friend constexpr typename Tag::type member(Tag) { return Member; }
};

#define FLUID_B2_MEMBER(Tag, Class, Type, Name)                                                    \
    struct Tag {                                                                                   \
        using type = Type Class::*;                                                                \
        friend constexpr type member(Tag);                                                         \
    };                                                                                             \
    template struct Expose<Tag, &Class::Name>;

// b2World
FLUID_B2_MEMBER(WorldContacts, b2World, b2ContactManager, m_contactManager)
FLUID_B2_MEMBER(WorldInvDt0, b2World, float, m_inv_dt0)
FLUID_B2_MEMBER(WorldNewContacts, b2World, bool, m_newContacts)
FLUID_B2_MEMBER(WorldStepComplete, b2World, bool, m_stepComplete)
// b2BroadPhase
FLUID_B2_MEMBER(PhaseTree, b2BroadPhase, b2DynamicTree, m_tree)
FLUID_B2_MEMBER(PhaseProxyCount, b2BroadPhase, int32, m_proxyCount)
FLUID_B2_MEMBER(PhaseMoveBuffer, b2BroadPhase, int32*, m_moveBuffer)
FLUID_B2_MEMBER(PhaseMoveCapacity, b2BroadPhase, int32, m_moveCapacity)
FLUID_B2_MEMBER(PhaseMoveCount, b2BroadPhase, int32, m_moveCount)
// b2DynamicTree
FLUID_B2_MEMBER(TreeRoot, b2DynamicTree, int32, m_root)
FLUID_B2_MEMBER(TreeNodes, b2DynamicTree, b2TreeNode*, m_nodes)
FLUID_B2_MEMBER(TreeNodeCount, b2DynamicTree, int32, m_nodeCount)
FLUID_B2_MEMBER(TreeNodeCapacity, b2DynamicTree, int32, m_nodeCapacity)
FLUID_B2_MEMBER(TreeFreeList, b2DynamicTree, int32, m_freeList)
FLUID_B2_MEMBER(TreeInsertions, b2DynamicTree, int32, m_insertionCount)
// b2Body
FLUID_B2_MEMBER(BodySweep, b2Body, b2Sweep, m_sweep)
FLUID_B2_MEMBER(BodyForce, b2Body, b2Vec2, m_force)
FLUID_B2_MEMBER(BodyTorque, b2Body, float, m_torque)
FLUID_B2_MEMBER(BodyInertia, b2Body, float, m_I)
FLUID_B2_MEMBER(BodyInvInertia, b2Body, float, m_invI)
FLUID_B2_MEMBER(BodySleepTime, b2Body, float, m_sleepTime)
FLUID_B2_MEMBER(BodyContacts, b2Body, b2ContactEdge*, m_contactList)
// b2Fixture
FLUID_B2_MEMBER(FixtureProxies, b2Fixture, b2FixtureProxy*, m_proxies)
FLUID_B2_MEMBER(FixtureProxyCount, b2Fixture, int32, m_proxyCount)
// b2Contact
FLUID_B2_MEMBER(ContactFlags, b2Contact, uint32, m_flags)
FLUID_B2_MEMBER(ContactPrev, b2Contact, b2Contact*, m_prev)
FLUID_B2_MEMBER(ContactNext, b2Contact, b2Contact*, m_next)
FLUID_B2_MEMBER(ContactNodeA, b2Contact, b2ContactEdge, m_nodeA)
FLUID_B2_MEMBER(ContactNodeB, b2Contact, b2ContactEdge, m_nodeB)
FLUID_B2_MEMBER(ContactToiCount, b2Contact, int32, m_toiCount)
FLUID_B2_MEMBER(ContactToi, b2Contact, float, m_toi)
// b2RevoluteJoint
FLUID_B2_MEMBER(RevoluteImpulse, b2RevoluteJoint, b2Vec2, m_impulse)
FLUID_B2_MEMBER(RevoluteMotorImpulse, b2RevoluteJoint, float, m_motorImpulse)
FLUID_B2_MEMBER(RevoluteLowerImpulse, b2RevoluteJoint, float, m_lowerImpulse)
FLUID_B2_MEMBER(RevoluteUpperImpulse, b2RevoluteJoint, float, m_upperImpulse)

#undef FLUID_B2_MEMBER

/// b2Contact::Create: the factory that makes the contact class for a pair of shape types.
struct ContactCreate {
    using type = b2Contact* (*)(b2Fixture*, int32, b2Fixture*, int32, b2BlockAllocator*);
    friend constexpr type member(ContactCreate);
};
template struct Expose<ContactCreate, &b2Contact::Create>;

/// The member `Tag` names of `object` (const when `object` is).
template <class Tag, class Object> decltype(auto) field(Object& object) {
    return (object.*member(Tag{}));
}

/// b2Contact's flags (Box2D 2.4.1, b2_contact.h).
enum ContactFlag : uint32 {
    kContactIsland = 0x0001,
    kContactTouching = 0x0002,
    kContactEnabled = 0x0004,
    kContactFilter = 0x0008,
    kContactBulletHit = 0x0010,
    kContactToi = 0x0020,
};

} // namespace fluid::box2d::detail
