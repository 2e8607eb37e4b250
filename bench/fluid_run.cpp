// fluid-run — plays a level file headless: progress on a terminal, per-frame statistics as CSV
// (the fluid, sensors, goal and Box2D bodies), level saves every K frames (which it also plays
// on from), plugin libraries loaded at run time.
//
//   fluid-run LEVEL.json|SAVE.level --frames N [--csv stats.csv] [--threads T]
//             [--snapshot-every K --out DIR] [--plugin lib.so]...
//
// Exit status: 0 when the run finished, 1 for bad input (the loader's message on stderr), 2 for
// a bad command line.
#include "command_line.h"

#include <fluid/box2d/coupling.h>
#include <fluid/fluid.h>
#include <fluid/level.h>
#include <fluid/plugin_library.h>

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

// CSV column names use the level's names; anything but letters, digits and '_' becomes '_'.
std::string columnName(const std::string& name) {
    std::string out = name;
    for (char& c : out) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        c = ok ? c : '_';
    }
    return out;
}

// Column names for a list of level names: sanitised, and made unique ("a-b" and "a_b" would
// both read "a_b": the second becomes "a_b_2").
template <class Id>
std::vector<std::string> columnNames(const std::vector<std::pair<std::string, Id>>& named) {
    std::vector<std::string> out;
    for (const auto& entry : named) {
        const std::string base = columnName(entry.first);
        std::string name = base;
        for (int k = 2; std::find(out.begin(), out.end(), name) != out.end(); ++k) {
            name = base + "_" + std::to_string(k);
        }
        out.push_back(name);
    }
    return out;
}

const char* goalText(fluid::GoalState state) {
    switch (state) {
    case fluid::GoalState::None:
        return "none";
    case fluid::GoalState::Pending:
        return "pending";
    case fluid::GoalState::Won:
        return "won";
    case fluid::GoalState::Lost:
        return "lost";
    }
    return "unknown";
}

// Extent and centre of mass of one material's particles.
struct MaterialStats {
    float xmin = std::numeric_limits<float>::infinity();
    float xmax = -std::numeric_limits<float>::infinity();
    float ymin = std::numeric_limits<float>::infinity();
    float ymax = -std::numeric_limits<float>::infinity();
    double sx = 0.0, sy = 0.0;
    uint32_t count = 0;
};

// The level's boundary shapes that ask for contact events ("contacts": true), with their
// column names and plugin indices, in file order.
std::vector<std::pair<std::string, uint32_t>> contactShapes(const fluid::Level& level) {
    std::vector<std::pair<std::string, uint32_t>> named;
    for (const fluid::Level::PluginEntry& p : level.plugins) {
        if (p.kind != fluid::PluginKind::Boundary) {
            continue;
        }
        const auto* shape =
            dynamic_cast<const fluid::KinematicShape*>(level.world.boundaries()[p.index].get());
        if (shape != nullptr && shape->contactEvents()) {
            named.emplace_back(p.name, p.index);
        }
    }
    return named;
}

// A contact's columns: particles, impulse x and y (N s), approach speed (m/s); all empty when
// the body stayed dry during the frame.
void writeContact(std::ostream& csv, const uint32_t* particles, glm::vec2 impulse, float speed) {
    if (particles == nullptr) {
        csv << ",0,,,";
        return;
    }
    csv << ',' << *particles << ',' << impulse.x << ',' << impulse.y << ',' << speed;
}

const char* const kContactColumns[] = {"_contact_particles", "_contact_ix", "_contact_iy",
                                       "_contact_speed"};

void writeHeader(std::ostream& csv, const fluid::Level& level) {
    csv << "frame,time,particles,substeps,kinetic_energy,density_error_mean,density_error_max";
    const std::vector<std::string> materials = columnNames(level.materials);
    for (const std::string& name : materials) {
        const std::string m = "m_" + name;
        csv << ',' << m << "_count," << m << "_xmin," << m << "_xmax," << m << "_ymin," << m
            << "_ymax," << m << "_cx," << m << "_cy";
    }
    for (const std::string& sensor : columnNames(level.sensors)) {
        for (const std::string& material : materials) {
            const std::string s = "s_" + sensor + "_" + material;
            csv << ',' << s << "_count," << s << "_volume";
        }
    }
    if (level.goal.present) {
        csv << ",goal_value,goal_state";
    }
    for (const std::string& body : columnNames(level.bodies)) {
        const std::string b = "b_" + body;
        csv << ',' << b << "_x," << b << "_y," << b << "_angle," << b << "_vx," << b << "_vy," << b
            << "_omega," << b << "_submerged";
    }
    // Contact events of the bodies and shapes that ask for them (docs/box2d.md, "Contact
    // events"): a level that asks for none keeps the columns above only.
    const std::vector<std::string> bodies = columnNames(level.bodies);
    for (std::size_t k = 0; k < level.bodies.size(); ++k) {
        if (level.coupling && level.coupling->contactEvents(level.bodies[k].second)) {
            for (const char* column : kContactColumns) {
                csv << ",b_" << bodies[k] << column;
            }
        }
    }
    for (const std::string& shape : columnNames(contactShapes(level))) {
        for (const char* column : kContactColumns) {
            csv << ",p_" << shape << column;
        }
    }
    csv << '\n';
}

void writeRow(std::ostream& csv, uint32_t frame, const fluid::Level& level) {
    const fluid::World& world = level.world;
    const auto px = world.positionX(), py = world.positionY();
    const auto vx = world.velocityX(), vy = world.velocityY();
    const auto mat = world.materialIndex();
    std::vector<MaterialStats> stats(world.materialCount());
    double kinetic = 0.0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        MaterialStats& s = stats[mat[i]];
        s.xmin = std::min(s.xmin, px[i]);
        s.xmax = std::max(s.xmax, px[i]);
        s.ymin = std::min(s.ymin, py[i]);
        s.ymax = std::max(s.ymax, py[i]);
        s.sx += px[i];
        s.sy += py[i];
        ++s.count;
        const double m = world.material(fluid::MaterialId{mat[i]}).mass;
        kinetic += 0.5 * m * (double(vx[i]) * vx[i] + double(vy[i]) * vy[i]);
    }
    // A coupled level steps the world once per round of the frame: the coupling sums them.
    const fluid::Profile& prof = level.coupling ? level.coupling->profile() : world.profile();
    csv << frame << ',' << world.time() << ',' << world.particleCount() << ',' << prof.substeps
        << ',' << kinetic << ',' << prof.densityErrorAvg << ',' << prof.densityErrorMax;
    for (const auto& [name, id] : level.materials) {
        const MaterialStats& s = stats[id.index];
        if (s.count == 0) {
            csv << ",0,,,,,,"; // no particles: no extent
            continue;
        }
        // One material has one mass, so its centre of mass is the mean position.
        csv << ',' << s.count << ',' << s.xmin << ',' << s.xmax << ',' << s.ymin << ',' << s.ymax
            << ',' << s.sx / s.count << ',' << s.sy / s.count;
    }
    for (const auto& [sensor, sid] : level.sensors) {
        const auto reading = world.sensorReading(sid);
        for (const auto& [material, mid] : level.materials) {
            csv << ',' << reading[mid.index].count << ',' << reading[mid.index].volume;
        }
    }
    if (level.goal.present) {
        csv << ',' << level.goalValue() << ',' << goalText(level.goalState());
    }
    for (const auto& [name, body] : level.bodies) {
        const b2Vec2 p = body->GetPosition(), v = body->GetLinearVelocity();
        csv << ',' << p.x << ',' << p.y << ',' << body->GetAngle() << ',' << v.x << ',' << v.y
            << ',' << body->GetAngularVelocity() << ',';
        // A body the coupling leaves out ("fluid": false) has no report: the cell stays empty.
        if (const fluid::box2d::BodyReport* report = level.coupling->report(body)) {
            csv << report->submergedFraction;
        }
    }
    for (const auto& [name, body] : level.bodies) {
        if (!level.coupling || !level.coupling->contactEvents(body)) {
            continue;
        }
        const fluid::box2d::ParticleContact* found = nullptr;
        for (const fluid::box2d::ParticleContact& c : level.coupling->particleContacts()) {
            found = c.body == body ? &c : found;
        }
        writeContact(csv, found != nullptr ? &found->particles : nullptr,
                     found != nullptr ? found->impulse : glm::vec2(0.0f),
                     found != nullptr ? found->approachSpeed : 0.0f);
    }
    for (const auto& [name, plugin] : contactShapes(level)) {
        const fluid::BodyContact* found = nullptr;
        for (const fluid::BodyContact& c : fluid::bodyContacts(world)) {
            found = c.plugin == plugin ? &c : found;
        }
        writeContact(csv, found != nullptr ? &found->particles : nullptr,
                     found != nullptr ? found->impulse : glm::vec2(0.0f),
                     found != nullptr ? found->approachSpeed : 0.0f);
    }
    csv << '\n';
}

// "[#######.............]  120/600 frames   57.3 fps" on one terminal line.
void progress(uint32_t done, uint32_t total, double fps) {
    constexpr int kWidth = 30;
    const int filled = total > 0 ? int(double(done) / total * kWidth) : kWidth;
    std::fprintf(stderr, "\r[%s%s] %u/%u frames %7.1f fps", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, '.').c_str(), done, total, fps);
    std::fflush(stderr);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"fluid-run: play a fluid level headless and report what happened"};
    std::string levelPath, csvPath, outDir;
    uint32_t frames = 0, threads = 0, snapshotEvery = 0;
    std::vector<std::string> plugins;
    app.add_option("level", levelPath,
                   "Level file (JSON, see docs/levels.md) or a level save (.level, as "
                   "--snapshot-every writes) to play on from")
        ->required();
    app.add_option("--frames", frames, "Frames to play (at the level's frame rate)")
        ->required()
        ->check(CLI::Range(1u, 100000000u));
    app.add_option("--csv", csvPath, "Write one row of statistics per frame to this file");
    app.add_option("--threads", threads, "Worker threads (default: the level's world.workers)")
        ->check(CLI::Range(1u, 256u));
    app.add_option("--snapshot-every", snapshotEvery,
                   "Save the level every K frames (needs --out): frame_K.level, a level save "
                   "that fluid-run plays on from")
        ->check(CLI::Range(1u, 100000000u));
    app.add_option("--out", outDir, "Directory for the level saves (created if missing)");
    app.add_option("--plugin", plugins,
                   "Plugin library (.so) to load before the level; repeatable");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        return status;
    }
    if (snapshotEvery > 0 && outDir.empty()) {
        std::cerr << "fluid-run: --snapshot-every needs --out DIR\n";
        return 2;
    }

    try {
        fluid::Registry registry;
        fluid::registerBuiltinPlugins(registry);
        for (const std::string& path : plugins) {
            const fluid::PluginLibrary lib = fluid::loadPluginLibrary(path, registry);
            std::cerr << "fluid-run: loaded " << lib.types.size() << " plugin type(s) from '"
                      << path << "'\n";
        }
        fluid::LevelOptions options;
        options.workerCount = threads;
        // A level save (Level::saveFile, the .level files below) continues where it was made:
        // a file that starts like one, or is named like one (an empty or damaged save is
        // refused as a save, not read as a level file). A world snapshot (World::saveFile,
        // which fluid-run wrote before its saves were level saves) is refused by its magic: it
        // holds the world without the level (goal, names, frame rate), and the JSON reader
        // would only say that 'F' is a syntax error.
        char magic[8] = {};
        {
            std::ifstream in(levelPath, std::ios::binary);
            in.read(magic, sizeof(magic));
        }
        if (std::string_view(magic, 8) == "FLUIDSNP") {
            throw fluid::Error(
                "fluid-run: '" + levelPath +
                    "' is a world snapshot (World::saveFile), not a level: it holds "
                    "no goal, names or frame rate to play on with; give a level file "
                    "(.json) or a level save (.level, as --snapshot-every writes)",
                fluid::ErrorCode::BadFile);
        }
        const bool isSave = std::filesystem::path(levelPath).extension() == ".level" ||
                            std::string_view(magic, 8) == "FLUIDLVL";
        fluid::Level level = isSave ? fluid::loadLevelSave(levelPath, registry, options)
                                    : fluid::loadLevel(levelPath, registry, options);
        for (const std::string& warning : level.warnings) {
            std::cerr << "fluid-run: warning: " << warning << '\n';
        }

        std::ofstream csv;
        if (!csvPath.empty()) {
            csv.open(csvPath, std::ios::trunc);
            if (!csv) {
                throw fluid::Error("fluid-run: cannot write '" + csvPath + "'",
                                   fluid::ErrorCode::Io);
            }
            csv << std::setprecision(9);
            writeHeader(csv, level);
        }
        if (snapshotEvery > 0) {
            std::filesystem::create_directories(outDir);
        }
        const bool terminal = isatty(fileno(stderr)) != 0;
        const Clock::time_point start = Clock::now();
        Clock::time_point lastShown = start;
        // Particles summed over the frames, each counted after its frame (unit: count): the
        // mean count and the cost per particle of a level whose count changes.
        double particleFrames = 0.0;
        for (uint32_t frame = 1; frame <= frames; ++frame) {
            level.step(); // one frame at the level's rate; the goal's state latches
            particleFrames += level.world.particleCount();
            if (csv.is_open()) {
                writeRow(csv, frame, level);
            }
            if (snapshotEvery > 0 && frame % snapshotEvery == 0) {
                // A level save: the level file's text, the world's snapshot and, with bodies,
                // the Box2D world and the coupling, so that fluid-run (and loadLevelSave) plays
                // on from it with the level's goal, names and frame rate.
                std::ostringstream name;
                name << "frame_" << std::setw(6) << std::setfill('0') << frame << ".level";
                level.saveFile((std::filesystem::path(outDir) / name.str()).string());
            }
            const Clock::time_point now = Clock::now();
            if (terminal && (now - lastShown > std::chrono::milliseconds(100) || frame == frames)) {
                const double seconds = std::chrono::duration<double>(now - start).count();
                progress(frame, frames, seconds > 0.0 ? frame / seconds : 0.0);
                lastShown = now;
            }
        }
        if (terminal) {
            std::fputc('\n', stderr);
        }
        if (csv.is_open()) {
            csv.close();
            if (!csv) {
                throw fluid::Error("fluid-run: writing '" + csvPath + "' failed",
                                   fluid::ErrorCode::Io);
            }
        }
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        std::printf("fluid-run: %s: %u frames (%.3f s simulated), %u particles, %.2f ms per frame",
                    level.name.empty() ? levelPath.c_str() : level.name.c_str(), frames,
                    level.world.time(), level.world.particleCount(), seconds * 1000.0 / frames);
        if (!level.bodies.empty()) {
            std::printf(", %zu bodies", level.bodies.size());
        }
        if (level.goal.present) {
            std::printf(", goal %s (%g)", goalText(level.goalState()), level.goalValue());
        }
        // The whole frame (Box2D and the coupling included) over the frames' mean particle
        // count; the time includes --csv and --snapshot-every writing when asked for.
        const double meanParticles = particleFrames / frames;
        std::printf("; mean %.0f particles, %.0f ns per particle per frame\n", meanParticles,
                    meanParticles > 0.0 ? seconds * 1e9 / particleFrames : 0.0);
    } catch (const fluid::Error& e) {
        std::cerr << e.what() << '\n';
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "fluid-run: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
