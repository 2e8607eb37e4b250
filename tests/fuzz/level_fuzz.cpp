// fluid — libFuzzer target for the level loader: any input must either load or throw
// fluid::Error (LevelError for anything in the text). Anything else is a finding: a crash, another
// exception type, a sanitizer report (ASan, UBSan), a hang or running out of memory.
//
// Build and run with scripts/fuzz.sh. By default the target only parses and builds the level
// (blobs are spawned, plugins and emitters created); it does not step the world, whose cost
// depends on the scene (a 100 km box container lays millions of wall samples) rather than on
// the loader. With FLUID_FUZZ_STEP=1 in the environment it also steps small levels once (at most
// 2,000 particles, no boundary plugin but the Box2D coupling's, Box2D fixtures of at most 100 m
// of outline), which reaches emitters, forces, drains, sensors, the coupling and b2World::Step
// with whatever values the loader accepts.
//
// An input that starts with FLUIDLVL is a level save (Level::save): its checksum is made right
// before reading (the fuzzer could never match it), so that the mutations reach every part of
// the reader (readLevelSave: the level text, world snapshot, Box2D world, coupling state and
// names). A save that loads is stepped for 3 frames (when it holds at most 2,000 particles and
// small bodies, as above, with or without FLUID_FUZZ_STEP), and a particle or Box2D body that is
// not finite after any of them is a finding (abort). scripts/fuzz.sh seeds it with a save of tests/fuzz/seeds/save_seed.json written by
// this binary: FLUID_FUZZ_WRITE_SAVE=LEVEL.json=OUT.level makes LLVMFuzzerInitialize load the
// level, step it twice and save it.
#include <fluid/level.h>
#include <fluid/plugins/builtin.h>

#include <box2d/box2d.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace {

const fluid::Registry& registry() {
    static const fluid::Registry instance = [] {
        fluid::Registry r;
        fluid::registerBuiltinPlugins(r);
        return r;
    }();
    return instance;
}

// True when the level's Box2D fixtures are small enough to step: the coupling samples every
// outline at the liquid's spacing, so a step costs in proportion to the perimeters (a 10 km box
// needs millions of samples), not to anything the loader does.
bool smallBodies(const fluid::Level& level) {
    if (!level.physics) {
        return true;
    }
    double perimeter = 0.0;
    for (const b2Body* b = level.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        for (const b2Fixture* f = b->GetFixtureList(); f != nullptr; f = f->GetNext()) {
            for (int32 child = 0; child < f->GetShape()->GetChildCount(); ++child) {
                b2AABB box;
                f->GetShape()->ComputeAABB(&box, b->GetTransform(), child);
                perimeter += double(box.GetPerimeter());
            }
        }
    }
    return perimeter < 100.0; // m: about 10,000 samples at water's spacing
}

// The bytes with their trailing FNV-1a 64 checksum made right (Level::save's).
std::string resealed(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    if (bytes.size() >= 20) {
        uint64_t h = 0xcbf29ce484222325ull;
        for (size_t k = 0; k + 8 < bytes.size(); ++k) {
            h ^= uint8_t(bytes[k]);
            h *= 0x100000001b3ull;
        }
        std::memcpy(bytes.data() + bytes.size() - 8, &h, 8);
    }
    return bytes;
}

// Frames an accepted save is stepped for (the first steps use the saved forces, debts and poses).
constexpr int kSaveFrames = 3;

// Aborts (a finding) unless every particle's position and velocity and every Box2D body's pose
// and velocities are finite after frame `frame` of a loaded save.
void requireFinite(const fluid::Level& level, int frame) {
    const fluid::World& world = level.world;
    for (const auto channel :
         {world.positionX(), world.positionY(), world.velocityX(), world.velocityY()}) {
        for (std::size_t i = 0; i < channel.size(); ++i) {
            if (!std::isfinite(channel[i])) {
                std::fprintf(stderr, "save stepped %d frames: particle %zu is not finite\n",
                             frame + 1, i);
                std::abort();
            }
        }
    }
    if (!level.physics) {
        return;
    }
    int k = 0;
    for (const b2Body* b = level.physics->GetBodyList(); b != nullptr; b = b->GetNext(), ++k) {
        const b2Vec2 p = b->GetPosition(), v = b->GetLinearVelocity();
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(b->GetAngle()) ||
            !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(b->GetAngularVelocity())) {
            std::fprintf(stderr, "save stepped %d frames: Box2D body %d is not finite\n",
                         frame + 1, k);
            std::abort();
        }
    }
}

bool stepWanted() {
    static const bool step = [] {
        const char* value = std::getenv("FLUID_FUZZ_STEP");
        return value != nullptr && std::strcmp(value, "1") == 0;
    }();
    return step;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
    const char* spec = std::getenv("FLUID_FUZZ_WRITE_SAVE");
    if (spec == nullptr) {
        return 0;
    }
    const std::string text(spec);
    const size_t eq = text.find('=');
    if (eq == std::string::npos) {
        std::fprintf(stderr, "FLUID_FUZZ_WRITE_SAVE: expected LEVEL.json=OUT.level\n");
        std::exit(2);
    }
    try {
        fluid::Level level = fluid::loadLevel(text.substr(0, eq), registry());
        level.step();
        level.step();
        level.saveFile(text.substr(eq + 1));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "FLUID_FUZZ_WRITE_SAVE: %s\n", e.what());
        std::exit(2);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fluid::LevelOptions options;
    // Memory and time per input stay small whatever the file asks: 20,000 particles at most,
    // and no thread pool (a file may ask for 256 workers).
    options.maxParticles = 20000;
    options.workerCount = 1;
    if (size >= 8 && std::memcmp(data, "FLUIDLVL", 8) == 0) {
        try {
            std::istringstream in(resealed(data, size));
            fluid::Level level = fluid::readLevelSave(in, "fuzz.level", registry(), options);
            (void)level.goalValue();
            // Whatever a save holds, an accepted one must step without a NaN or an infinity
            // (a huge finite impulse once turned a body NaN at its first step, silently).
            if (level.world.particleCount() <= 2000 && smallBodies(level)) {
                for (int frame = 0; frame < kSaveFrames; ++frame) {
                    level.step();
                    requireFinite(level, frame);
                }
            }
        } catch (const fluid::Error&) {
            // Refused with a message.
        }
        return 0;
    }
    try {
        fluid::Level level =
            fluid::parseLevel(std::string_view(reinterpret_cast<const char*>(data), size),
                              "fuzz.json", registry(), options);
        // The goal accessors read sensors and materials by the ids the loader stored.
        (void)level.goalValue();
        (void)level.goalState();
        const bool step = stepWanted();
        // The only boundary allowed is the Box2D coupling's, with small bodies.
        const std::size_t coupled = level.coupling ? 1 : 0;
        if (step && level.world.particleCount() <= 2000 &&
            level.world.boundaries().size() == coupled && smallBodies(level)) {
            level.step();
            (void)level.goalState();
        }
    } catch (const fluid::Error&) {
        // Rejected with a message: the expected outcome for almost every input.
    }
    return 0;
}
