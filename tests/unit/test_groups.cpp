// Groups, per-particle user data and colours (fluid/groups.h): membership, user data and colours
// follow their particles by handle through sorts, steps, saves and restores bit for bit; centre
// and velocity equal a brute-force sum; move, velocity, destroy and merge do what they say to
// exactly the group's particles; stale handles and bad values refused with the value named;
// colour mixing keeps every channel's sum and gives the same colours on 1, 2 and 4 workers.
#include "test_support.h"

#include <fluid/groups.h>

#include <catch2/catch.hpp>

#include <cstring>
#include <map>
#include <sstream>

using namespace fluid;
using namespace fluid::test;

namespace {

// Two coloured blobs side by side in a closed tank, an emitter pouring a third colour, all
// three groups: the liquid sloshes, so the sort reorders the arrays every sub-step.
struct GroupScene {
    World world;
    GroupHandle left, right, poured;
    EmitterId emitter;
};

GroupScene colouredTank(uint32_t workers, float mixing = 0.0f) {
    WorldDef def;
    def.workerCount = workers;
    GroupScene sc{World(def), {}, {}, {}, {}};
    World& world = sc.world;
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(-0.3f, 0.0f, 0.3f, 0.6f));
    sc.left = spawnGroup(world, latticeBlock(world, w, -0.3f, 0.0f, 20, 24),
                         GroupDef{11, Colour{255, 0, 0, 255}});
    sc.right = spawnGroup(world, latticeBlock(world, w, 0.05f, 0.0f, 20, 24),
                          GroupDef{22, Colour{0, 0, 255, 255}});
    EmitterDef e;
    e.position = {0.0f, 0.5f};
    e.direction = {0.0f, -1.0f};
    e.speed = 1.0f;
    e.rate = 200.0f;
    e.maxCount = 150;
    e.material = w;
    sc.emitter = world.addEmitter(e);
    sc.poured = emitterGroup(world, sc.emitter);
    setGroupDef(world, sc.poured, GroupDef{33, Colour{0, 255, 0, 255}});
    setColourMixing(world, mixing);
    return sc;
}

// What a game would record per particle, by handle.
struct Tag {
    GroupHandle group;
    uint32_t userData = 0;
    Colour colour;
};

std::map<std::pair<uint32_t, uint32_t>, Tag> tags(const World& world) {
    std::map<std::pair<uint32_t, uint32_t>, Tag> out;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const ParticleHandle h = world.handleAt(i);
        out[{h.slot, h.generation}] = Tag{groupOf(world, h), userData(world, h), colour(world, h)};
    }
    return out;
}

uint64_t channelSum(const World& world, int channel) {
    uint64_t sum = 0;
    for (const uint32_t c : colours(world)) {
        sum += (c >> (8 * channel)) & 255u;
    }
    return sum;
}

} // namespace

TEST_CASE("groups: blobs and emitters are groups whose particles keep group, user data and "
          "colour by handle across many steps",
          "[groups]") {
    GroupScene sc = colouredTank(2);
    World& world = sc.world;
    const uint32_t blob = 20 * 24;
    CHECK(groupCount(world, sc.left) == blob);
    CHECK(groupCount(world, sc.right) == blob);
    CHECK(groupCount(world, sc.poured) == 0);
    CHECK(colours(world).size() == world.particleCount());
    // The game's own per-particle tags, set by handle, distinct per particle.
    for (uint32_t i = 0; i < world.particleCount(); i += 3) {
        const ParticleHandle h = world.handleAt(i);
        setUserData(world, h, 1000u + h.slot * 7u);
        setColour(world, h, Colour{uint8_t(h.slot), uint8_t(h.slot >> 8), 77, 200});
    }
    auto before = tags(world);
    for (int frame = 0; frame < 90; ++frame) {
        world.step(kFrame);
        if (frame == 30) {
            // Particles the emitter added since: they joined its group with its user data and
            // colour.
            for (const auto& [key, tag] : tags(world)) {
                if (!before.contains(key)) {
                    CHECK(tag.group == sc.poured);
                    CHECK(tag.userData == 33u);
                    CHECK(tag.colour == (Colour{0, 255, 0, 255}));
                    before[key] = tag;
                }
            }
        }
    }
    REQUIRE(world.emittedCount(sc.emitter) == 150);
    const auto after = tags(world);
    uint32_t emittedLate = 0;
    for (const auto& [key, tag] : after) {
        const auto old = before.find(key);
        if (old == before.end()) {
            ++emittedLate;
            CHECK(tag.group == sc.poured);
            continue;
        }
        CHECK(tag.group == old->second.group);
        CHECK(tag.userData == old->second.userData);
        CHECK(tag.colour == old->second.colour);
    }
    CHECK(emittedLate > 0);
    CHECK(groupCount(world, sc.poured) == 150);
    CHECK(groupCount(world, sc.left) + groupCount(world, sc.right) + groupCount(world, sc.poured) ==
          world.particleCount());
    // The buffer forms agree with the handle forms.
    std::vector<uint32_t> data(world.particleCount());
    CHECK(fillUserData(world, data) == world.particleCount());
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        CHECK(data[i] == userData(world, world.handleAt(i)));
        CHECK(colours(world)[i] == colour(world, world.handleAt(i)).pack());
    }
    std::vector<ParticleHandle> members(groupCount(world, sc.left));
    CHECK(groupParticles(world, sc.left, members) == members.size());
    uint32_t last = 0;
    for (size_t k = 0; k < members.size(); ++k) {
        const uint32_t index = *world.indexOf(members[k]);
        CHECK(groupOf(world, members[k]) == sc.left);
        CHECK((k == 0 || index > last)); // increasing array index
        last = index;
    }
}

TEST_CASE("groups: centre of mass and velocity equal a brute-force sum", "[groups]") {
    GroupScene sc = colouredTank(1);
    World& world = sc.world;
    for (int frame = 0; frame < 40; ++frame) {
        world.step(kFrame);
    }
    for (const GroupHandle g : {sc.left, sc.right, sc.poured}) {
        double m = 0, x = 0, y = 0, vx = 0, vy = 0;
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            if (groupOf(world, world.handleAt(i)) != g) {
                continue;
            }
            const double mi = world.material(MaterialId{world.materialIndex()[i]}).mass;
            m += mi;
            x += mi * world.positionX()[i];
            y += mi * world.positionY()[i];
            vx += mi * world.velocityX()[i];
            vy += mi * world.velocityY()[i];
        }
        REQUIRE(m > 0.0);
        CHECK(groupCentre(world, g) == glm::vec2(float(x / m), float(y / m)));
        CHECK(groupVelocity(world, g) == glm::vec2(float(vx / m), float(vy / m)));
    }
    const GroupHandle empty = createGroup(world);
    CHECK(groupCentre(world, empty) == glm::vec2(0.0f, 0.0f));
    CHECK(groupVelocity(world, empty) == glm::vec2(0.0f, 0.0f));
}

TEST_CASE("groups: move, velocity, destroy and merge act on exactly the group's particles",
          "[groups]") {
    GroupScene sc = colouredTank(1);
    World& world = sc.world;
    setInterpolation(world, true);
    for (int frame = 0; frame < 20; ++frame) {
        world.step(kFrame);
    }
    const std::vector<glm::vec2> x0 = positions(world);
    moveGroup(world, sc.left, {0.0f, 0.125f});
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const bool member = groupOf(world, world.handleAt(i)) == sc.left;
        CHECK(world.positionX()[i] == x0[i].x);
        CHECK(world.positionY()[i] == (member ? x0[i].y + 0.125f : x0[i].y));
        if (member) { // moved, not flown: the previous position moved along
            CHECK(previousPositionY(world)[i] == world.positionY()[i]);
            CHECK(previousPositionX(world)[i] == world.positionX()[i]);
        }
    }
    // All or nothing: a move out of the position range is refused, nothing moved.
    CHECK_THROWS_WITH(moveGroup(world, sc.left, {1e9f, 0.0f}),
                      Catch::Matchers::StartsWith("moveGroup: particle ") &&
                          Catch::Matchers::Contains("'s new position = (") &&
                          Catch::Matchers::Contains("is outside the position range"));
    CHECK_THROWS_WITH(moveGroup(world, sc.left, {NAN, 0.0f}),
                      "moveGroup: offset = (nan, 0) is not finite (unit: m)");
    CHECK(world.positionY()[0] == positions(world)[0].y);

    setGroupVelocity(world, sc.right, {0.5f, -0.25f});
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (groupOf(world, world.handleAt(i)) == sc.right) {
            CHECK(world.velocityX()[i] == 0.5f);
            CHECK(world.velocityY()[i] == -0.25f);
        }
    }
    CHECK(groupVelocity(world, sc.right) == glm::vec2(0.5f, -0.25f));
    CHECK_THROWS_WITH(setGroupVelocity(world, sc.right, {0.0f, INFINITY}),
                      "setGroupVelocity: velocity = (0, inf) is not finite (unit: m/s)");

    // Merge: the poured group's particles join the left one; the poured handle goes stale and
    // the emitter feeds the left group from now on.
    for (int frame = 0; frame < 30; ++frame) {
        world.step(kFrame);
    }
    const uint32_t left = groupCount(world, sc.left), poured = groupCount(world, sc.poured);
    REQUIRE(poured > 0);
    mergeGroups(world, sc.left, sc.poured);
    CHECK(groupCount(world, sc.left) == left + poured);
    CHECK_FALSE(isValid(world, sc.poured));
    CHECK(emitterGroup(world, sc.emitter) == sc.left);
    CHECK_THROWS_WITH(mergeGroups(world, sc.left, sc.left),
                      "mergeGroups: into and from are the same group {index 0}; merge two "
                      "different groups");

    // Destroy with particles: exactly the right group's particles go, the others stay.
    const uint32_t total = world.particleCount(), right = groupCount(world, sc.right);
    const auto before = tags(world);
    destroyGroup(world, sc.right);
    CHECK(world.particleCount() == total - right);
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        CHECK(groupOf(world, world.handleAt(i)) == sc.left);
    }
    for (const auto& [key, tag] : before) {
        const ParticleHandle h{key.first, key.second, sc.left.world};
        CHECK(world.isValid(h) == (tag.group != sc.right));
    }
    CHECK_FALSE(isValid(world, sc.right));
    // Destroy without particles: they stay, without a group.
    const uint32_t kept = world.particleCount();
    destroyGroup(world, sc.left, false);
    CHECK(world.particleCount() == kept);
    CHECK(groupOf(world, world.handleAt(0)).isNull());
    // The emitter that fed a destroyed group gets a new one.
    const GroupHandle fresh = emitterGroup(world, sc.emitter);
    CHECK(isValid(world, fresh));
    CHECK(groupCount(world, fresh) == 0);
    // The interpolation channel stayed in step with the removals.
    CHECK(previousPositionX(world).size() == world.particleCount());
    CHECK(colours(world).size() == world.particleCount());
}

TEST_CASE("groups: stale, null and foreign handles and bad values are refused by name",
          "[groups]") {
    GroupScene sc = colouredTank(1);
    World& world = sc.world;
    destroyGroup(world, sc.right);
    CHECK_THROWS_WITH(groupCount(world, sc.right),
                      "groupCount: stale group handle {index 1, generation 1}: that group was "
                      "destroyed or merged into another");
    CHECK_THROWS_WITH(moveGroup(world, sc.right, {0.0f, 0.0f}),
                      "moveGroup: stale group handle {index 1, generation 1}: that group was "
                      "destroyed or merged into another");
    // The entry is reused with a new generation: the old handle stays stale.
    const GroupHandle reused = createGroup(world);
    CHECK(reused.index == sc.right.index);
    CHECK(reused.generation == sc.right.generation + 1);
    CHECK_FALSE(isValid(world, sc.right));
    CHECK_THROWS_WITH(groupCentre(world, GroupHandle{}), "groupCentre: null group handle");
    GroupScene other = colouredTank(1);
    CHECK_THROWS_WITH(
        groupCount(world, other.left),
        "groupCount: group handle {index 0, generation 1} belongs to another world (world " +
            std::to_string(other.left.world) + "; this is world " + std::to_string(sc.left.world) +
            "; a handle saved with a snapshot needs fluid::adopt)");
    BlobDef blob = latticeBlock(world, MaterialId{0}, -0.1f, 0.3f, 4, 4);
    blob.group = sc.right;
    CHECK_THROWS_WITH(world.spawnBlob(blob),
                      "spawnBlob: stale group handle {index 1, generation 1}: that group was "
                      "destroyed or merged into another");
    const uint32_t count = world.particleCount();
    CHECK_THROWS_AS(spawnGroup(world, blob), Error);
    CHECK(world.particleCount() == count);
    CHECK_THROWS_WITH(setColourMixing(world, -1.0f),
                      Catch::Matchers::StartsWith("setColourMixing: rate = -1 is out of range"));
    CHECK_THROWS_WITH(setColourMixing(world, NAN),
                      Catch::Matchers::StartsWith("setColourMixing: rate = nan is out of range"));
    CHECK_THROWS_WITH(emitterGroup(world, EmitterId{5}),
                      "emitterGroup: unknown emitter id 5; the world has 1 emitters");
    const ParticleHandle h = world.handleAt(0);
    world.removeParticle(h);
    CHECK_THROWS_WITH(userData(world, h), Catch::Matchers::StartsWith("userData: stale particle "
                                                                      "handle {slot "));
    CHECK_THROWS_WITH(setColour(world, h, Colour{1, 2, 3, 4}),
                      Catch::Matchers::StartsWith("setColour: stale particle handle {slot "));
    // A removed particle's slot, reused, starts without user data or a group.
    const ParticleHandle again = world.addParticle({0.0f, 0.3f}, {0.0f, 0.0f}, MaterialId{0});
    CHECK(again.slot == h.slot);
    CHECK(userData(world, again) == 0u);
    CHECK(groupOf(world, again).isNull());
    CHECK(colour(world, again) == Colour{});
}

TEST_CASE("groups: calls during the world's step are refused with WrongState", "[groups]") {
    GroupScene sc = colouredTank(1);
    World& world = sc.world;
    bool called = false;
    world.addForce(std::make_unique<HookForce>([&] {
        called = true;
        try {
            (void)groupCount(world, sc.left);
            FAIL("groupCount ran during the step");
        } catch (const Error& e) {
            CHECK(e.code() == ErrorCode::WrongState);
            CHECK_THAT(e.what(), Catch::Matchers::StartsWith("groupCount: called during the "
                                                             "world's own step"));
        }
        CHECK_THROWS_AS(moveGroup(world, sc.left, {0.0f, 0.1f}), Error);
        CHECK_THROWS_AS(setInterpolation(world, true), Error);
    }));
    world.step(kFrame);
    CHECK(called);
}

TEST_CASE("groups: groups, user data and colours survive a save and restore bit for bit",
          "[groups][snapshot]") {
    GroupScene sc = colouredTank(2, 4.0f);
    World& world = sc.world;
    setInterpolation(world, true);
    for (int frame = 0; frame < 30; ++frame) {
        world.step(kFrame);
    }
    for (uint32_t i = 0; i < world.particleCount(); i += 5) {
        setUserData(world, world.handleAt(i), 0xABCD0000u + i);
    }
    destroyGroup(world, createGroup(world)); // a free entry in the table
    const std::string bytes = saved(world);
    World copy = restored(bytes);
    CHECK(saved(copy) == bytes); // the same state, the same bytes
    CHECK(tags(copy).size() == tags(world).size());
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const ParticleHandle h = world.handleAt(i), c = copy.handleAt(i);
        CHECK(c.slot == h.slot);
        CHECK(groupOf(copy, c) == adopt(copy, groupOf(world, h)));
        CHECK(userData(copy, c) == userData(world, h));
    }
    CHECK(std::equal(colours(copy).begin(), colours(copy).end(), colours(world).begin()));
    CHECK(colourMixing(copy) == 4.0f);
    CHECK(interpolating(copy));
    // A loaded world's previous positions are its current ones: nothing streaks.
    CHECK(std::equal(previousPositionX(copy).begin(), previousPositionX(copy).end(),
                     copy.positionX().begin()));
    // Both go on the same way, colours mixing, the emitter pouring into its group.
    for (int frame = 0; frame < 40; ++frame) {
        world.step(kFrame);
        copy.step(kFrame);
    }
    CHECK(stateHash(copy) == stateHash(world));
    CHECK(std::equal(colours(copy).begin(), colours(copy).end(), colours(world).begin(),
                     colours(world).end()));
    CHECK(groupCount(copy, adopt(copy, sc.poured)) == groupCount(world, sc.poured));
    std::vector<float> ax(world.particleCount()), ay(ax.size()), bx(ax.size()), by(ax.size());
    interpolatedPositions(world, ax, ay);
    interpolatedPositions(copy, bx, by);
    CHECK(ax == bx);
    CHECK(ay == by);
}

TEST_CASE("groups: a version 6 snapshot (before groups) still loads", "[groups][snapshot]") {
    WorldDef def;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    for (int k = 0; k < 10; ++k) {
        world.addParticle({0.01f * float(k), 0.0f}, {0.0f, 0.0f}, w);
    }
    std::string bytes = saved(world);
    // Version 7's last section for a world without groups, emitters, user data or colours:
    // flag, rate, an empty group table and six empty arrays.
    const size_t tail = 1 + 4 + 8 + 6 * 8;
    const size_t header = 8 + 4 + 8;
    uint64_t size = 0;
    std::memcpy(&size, bytes.data() + 12, 8);
    REQUIRE(bytes.size() == header + size + 8);
    std::string payload = bytes.substr(header, size - tail);
    const uint32_t version = 6;
    const uint64_t shorter = payload.size();
    uint64_t sum = 14695981039346656037ull;
    for (const char c : payload) {
        sum ^= uint8_t(c);
        sum *= 1099511628211ull;
    }
    std::string old = bytes.substr(0, 8);
    old.append(reinterpret_cast<const char*>(&version), 4);
    old.append(reinterpret_cast<const char*>(&shorter), 8);
    old += payload;
    old.append(reinterpret_cast<const char*>(&sum), 8);
    World loaded = restored(old);
    CHECK(loaded.particleCount() == 10);
    CHECK(positions(loaded) == positions(world));
    CHECK(groupOf(loaded, loaded.handleAt(3)).isNull());
    CHECK(colours(loaded).empty());
    CHECK_FALSE(interpolating(loaded));
    CHECK(saved(loaded) == bytes); // saved again as version 7
}

TEST_CASE("groups: colour mixing keeps each channel's sum and is the same on 1, 2 and 4 "
          "workers",
          "[groups][determinism]") {
    std::vector<uint32_t> reference;
    uint64_t referenceHash = 0;
    for (const uint32_t workers : {1u, 2u, 4u}) {
        GroupScene sc = colouredTank(workers, 3.0f);
        World& world = sc.world;
        world.setEmitter(sc.emitter, [&] {
            EmitterDef e = world.emitter(sc.emitter);
            e.rate = 0.0f; // a closed box: no particle comes or goes
            return e;
        }());
        uint64_t sums[4];
        for (int c = 0; c < 4; ++c) {
            sums[c] = channelSum(world, c);
        }
        const auto count = uint64_t(world.particleCount());
        const std::vector<uint32_t> start(colours(world).begin(), colours(world).end());
        for (int frame = 0; frame < 60; ++frame) {
            world.step(kFrame);
            // Kept exactly at 1/256 of a level: the visible bytes (the fractions cut off) sum
            // to at most the start's and less than one level per particle below it.
            for (int c = 0; c < 4; ++c) {
                const uint64_t now = channelSum(world, c);
                CHECK(now <= sums[c]);
                CHECK(now + count > sums[c]);
            }
        }
        // The colours did mix: some particles are now neither pure red nor pure blue.
        uint32_t mixed = 0;
        for (const uint32_t c : colours(world)) {
            mixed += (c != start.front() && c != start.back()) ? 1 : 0;
        }
        CHECK(mixed > 50);
        // Compared by handle order (the arrays' order is the same too: same sorts).
        const std::vector<uint32_t> now(colours(world).begin(), colours(world).end());
        if (reference.empty()) {
            reference = now;
            referenceHash = stateHash(world);
        } else {
            CHECK(now == reference);
            CHECK(stateHash(world) == referenceHash);
        }
    }
}
