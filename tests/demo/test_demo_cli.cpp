// fluid-demo's command line: bad input gets a clear message and a distinct exit status
// (2 command line, 1 level file, 77 no display), never a crash or a window.
#include "demo_support.h"

using demo_test::Run;
using demo_test::runDemo;

TEST_CASE("fluid-demo: an unknown level is a command-line error listing the levels", "[demo]") {
    const Run run = runDemo("--level no_such_level --frames 1 --screenshot /dev/null");
    CHECK(run.status == 2);
    CHECK(run.output.rfind("fluid-demo: no level 'no_such_level' in " FLUID_DEMO_LEVELS_DIR
                           " (levels: dam_break, yoghurt_vs_water, zero_g_arena, crates, ",
                           0) == 0);
}

TEST_CASE("fluid-demo: a bad size and a missing screenshot target are command-line errors",
          "[demo]") {
    Run run = runDemo("--level dam_break --frames 1 --screenshot x.png --size 10x10");
    CHECK(run.status == 2);
    CHECK(run.output == "fluid-demo: --size '10x10' is not WxH with each in [16, 8192] pixels\n");
    run = runDemo("--level dam_break --frames 5");
    CHECK(run.status == 2);
    CHECK(run.output == "fluid-demo: --frames needs --screenshot FILE or --screenshot-dir DIR\n");
    run = runDemo("--level all --frames 5 --screenshot one.png");
    CHECK(run.status == 2);
    CHECK(run.output == "fluid-demo: --screenshot FILE takes one level and one view; use "
                        "--screenshot-dir for several\n");
}

TEST_CASE("fluid-demo: a malformed level file exits 1 with the loader's located message",
          "[demo]") {
    const Run run = runDemo("--level '" FLUID_TEST_DATA_DIR
                            "/bad_plugin_param.json' --frames 1 --screenshot /dev/null");
    CHECK(run.status == 1);
    // The last line (SFML may warn about vertical sync on a virtual display before it).
    const std::string message = "fluid-demo: " FLUID_TEST_DATA_DIR
                                "/bad_plugin_param.json:11:27: at /plugins/0/params/radius: 0 is "
                                "out of range [0.0001, 10000] (unit: m)\n";
    CHECK(run.output.ends_with(message));
    CHECK((run.output == message || run.output.ends_with("\n" + message)));
}

TEST_CASE("fluid-demo: headless without a display exits 77 and says how to run it", "[demo]") {
    const Run run = runDemo("--level dam_break --frames 1 --screenshot x.png", "env -u DISPLAY");
    CHECK(run.status == 77);
    CHECK(run.output.find("no display (DISPLAY is not set); run it under Xvfb:") !=
          std::string::npos);
}
