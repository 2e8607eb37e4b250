// The C API's statuses from the C++ error codes (docs/errors.md): every code maps to the one
// status documented for it, every status but FLUID_OK and FLUID_ERROR_NULL_ARGUMENT comes from
// exactly the codes documented, and each kind reaches C with its status and the C++ message.
#include "c_test_support.h"

#include "c_status.h"

#include <fluid/error.h>
#include <fluid/world.h>

#include <cstring>
#include <map>
#include <set>
#include <string>

using namespace fluid;
using fluid::test::CWorld;

TEST_CASE("C status: every error code maps to the status documented for it", "[c][errors]") {
    // The table of docs/errors.md.
    const std::map<fluid_status, std::set<ErrorCode>> documented{
        {FLUID_ERROR_INVALID_ARGUMENT, {ErrorCode::BadArgument, ErrorCode::OutOfRange}},
        {FLUID_ERROR_REFUSED, {ErrorCode::WrongState}},
        {FLUID_ERROR_STALE_ID, {ErrorCode::StaleId}},
        {FLUID_ERROR_UNKNOWN_NAME, {ErrorCode::UnknownName}},
        {FLUID_ERROR_LIMIT, {ErrorCode::Full}},
        {FLUID_ERROR_BAD_FILE, {ErrorCode::BadFile}},
        {FLUID_ERROR_IO, {ErrorCode::Io}},
        {FLUID_ERROR_OUT_OF_MEMORY, {ErrorCode::OutOfMemory}},
    };
    std::map<fluid_status, std::set<ErrorCode>> mapped;
    for (const EnumName<ErrorCode>& row : kErrorCodeNames) {
        const fluid_status status = fluid::c::statusOf(row.value);
        INFO(row.name << " -> " << fluid_status_name(status));
        CHECK(status != FLUID_OK);
        CHECK(status != FLUID_ERROR_NULL_ARGUMENT); // the C layer's own
        CHECK(std::string(fluid_status_name(status)) != "unknown status");
        mapped[status].insert(row.value);
    }
    CHECK(mapped == documented);
    // Every status the header lists has a home: the codes above, or the C layer itself.
    for (int s = FLUID_ERROR_INVALID_ARGUMENT; s <= FLUID_ERROR_REFUSED; ++s) {
        INFO(fluid_status_name(fluid_status(s)));
        CHECK((documented.count(fluid_status(s)) == 1 || s == FLUID_ERROR_NULL_ARGUMENT));
    }
}

TEST_CASE("C status: each kind of C++ error reaches C with its status and message", "[c][errors]") {
    CWorld w(fluid_default_world_def());
    fluid_material_def water{};
    C_OK(fluid_material_preset("water", &water));
    fluid_material_id id{};
    C_OK(fluid_world_add_material(w.world, &water, &id));

    // Out of range: a frame time.
    CHECK(fluid_world_step(w.world, -1.0f) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()).rfind("World::step: frameDt = -1 s is out of range", 0) ==
          0);
    // A stale id: a particle removed twice.
    fluid_particle_id p{};
    C_OK(fluid_world_add_particle(w.world, {0.0f, 0.0f}, {0.0f, 0.0f}, id, &p));
    C_OK(fluid_world_remove_particle(w.world, p));
    CHECK(fluid_world_remove_particle(w.world, p) == FLUID_ERROR_STALE_ID);
    // An unknown name: a quality, with the names of the one table.
    fluid_world_def def = fluid_default_world_def();
    CHECK(fluid_world_def_set_quality(&def, "ultra") == FLUID_ERROR_UNKNOWN_NAME);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_def_set_quality: unknown quality 'ultra' (expected game or precise)");
    for (const EnumName<Quality>& row : kQualityNames) {
        C_OK(fluid_world_def_set_quality(&def, std::string(row.name).c_str()));
    }
    // A level naming a plugin type nothing registered: an unknown name, located in the file.
    const char* const level =
        R"({"version": 1, "materials": [{"name": "water"}], "plugins": [{"type": "force.vortx"}]})";
    fluid_level* made = nullptr;
    CHECK(fluid_level_parse(level, std::strlen(level), "t.json", nullptr, &made) ==
          FLUID_ERROR_UNKNOWN_NAME);
    CHECK(std::string(fluid_last_error())
              .rfind("t.json:1:71: at /plugins/0/type: unknown plugin type 'force.vortx'; known: ",
                     0) == 0);
    CHECK(made == nullptr);
    // A bad file: malformed JSON, bytes that are not a snapshot.
    const char* const broken = "{\"version\": 1,";
    CHECK(fluid_level_parse(broken, std::strlen(broken), "t.json", nullptr, &made) ==
          FLUID_ERROR_BAD_FILE);
    const char garbage[] = "not a snapshot";
    fluid_world* loaded = nullptr;
    CHECK(fluid_world_load(garbage, sizeof garbage, 0, &loaded) == FLUID_ERROR_BAD_FILE);
    CHECK(std::string(fluid_last_error()) == "snapshot: not a fluid snapshot (no FLUIDSNP header)");
    // I/O: a file that cannot be opened.
    CHECK(fluid_level_load("/nonexistent/level.json", nullptr, &made) == FLUID_ERROR_IO);
    CHECK(std::string(fluid_last_error())
              .rfind("loadLevel: cannot open '/nonexistent/level.json'", 0) == 0);
    // Full: the particle cap.
    fluid_blob_def blob = fluid_default_blob_def();
    blob.material = id;
    blob.shape = fluid_box_shape({0.0f, 0.0f}, {80.0f, 80.0f});
    CHECK(fluid_world_spawn_blob(w.world, &blob, nullptr) == FLUID_ERROR_LIMIT);
}
