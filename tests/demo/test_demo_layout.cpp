// Where the demo's overlays go (demo/layout.h): the HUD and the level banner keep to a band
// across the top, every shipped level is framed below it, and the HUD and the banner stay
// inside their boxes however small the window. Geometry only: no window, no GL context (ImGui
// lays the overlays out without a renderer).
#include "demo/banner.h"
#include "demo/hud.h"
#include "demo/layout.h"
#include "demo/level_list.h"
#include "demo/session.h"

#include <fluid/gl/shapes.h>

#include <catch2/catch.hpp>
#include <glm/common.hpp>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {
using fluid::demo::OverlayLayout;
using fluid::demo::PixelRect;

// The window sizes the levels are checked at: the default, the screenshots' and the smaller
// page sizes.
const glm::ivec2 kSizes[] = {{1280, 720}, {960, 540}, {640, 360}};

// The pixel rectangle everything the level draws (walls, sensors, drains, nozzles, bodies)
// covers through `camera`.
PixelRect drawnBounds(const fluid::demo::Session& session, const fluid::gl::Camera& camera) {
    fluid::gl::ShapeBatch under, over;
    session.drawShapes(camera, false, under, over);
    PixelRect box{glm::vec2(std::numeric_limits<float>::max()),
                  glm::vec2(std::numeric_limits<float>::lowest())};
    for (const fluid::gl::ShapeBatch* batch : {&under, &over}) {
        for (const auto& vertex : batch->vertices()) {
            const glm::vec2 p = camera.worldToPixel(vertex.position);
            box.min = glm::min(box.min, p);
            box.max = glm::max(box.max, p);
        }
    }
    return box;
}

// An ImGui context without a renderer, for laying the overlays out.
struct ImGuiLayout {
    explicit ImGuiLayout(glm::ivec2 size) {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(float(size.x), float(size.y));
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    }
    ~ImGuiLayout() { ImGui::DestroyContext(); }
    ImGuiLayout(const ImGuiLayout&) = delete;
    ImGuiLayout& operator=(const ImGuiLayout&) = delete;

    // Runs `draw` for three frames (auto-resized windows take their size from the frame
    // before) and returns the rectangle of the window `name`.
    template <class F> PixelRect window(const char* name, F&& draw) {
        for (int frame = 0; frame < 3; ++frame) {
            ImGui::NewFrame();
            draw();
            ImGui::EndFrame();
        }
        const ImGuiWindow* window = ImGui::FindWindowByName(name);
        REQUIRE(window != nullptr);
        return {{window->Pos.x, window->Pos.y},
                {window->Pos.x + window->Size.x, window->Pos.y + window->Size.y}};
    }
};

bool inside(const PixelRect& inner, const PixelRect& outer) {
    return inner.min.x >= outer.min.x - 0.5f && inner.min.y >= outer.min.y - 0.5f &&
           inner.max.x <= outer.max.x + 0.5f && inner.max.y <= outer.max.y + 0.5f;
}

// Every line the HUD can show.
fluid::demo::HudInfo fullHud() {
    fluid::demo::HudInfo hud;
    hud.fps = 59.0f;
    hud.particles = 12345;
    hud.simMsPerFrame = 12.3f;
    hud.substeps = 4;
    hud.view = "metaballs";
    hud.material = "yoghurt";
    hud.paused = true;
    hud.behind = true;
    hud.speed = 0.71;
    hud.droppedSteps = 123;
    hud.cursor = "water, 3.6 cm deep, 507 Pa, 0.01 m/s";
    hud.laser = "hits water at (0.32, 0.07) m, 0.41 m away";
    return hud;
}
} // namespace

TEST_CASE("every shipped level is framed below the band the HUD and the banner keep to",
          "[demo][layout]") {
    const auto levels = fluid::demo::listLevels(FLUID_DEMO_LEVELS_DIR);
    REQUIRE(levels.size() >= 14);
    for (const glm::ivec2 size : kSizes) {
        const OverlayLayout layout = fluid::demo::overlayLayout(size);
        // Both overlays' boxes end in the band.
        CHECK(layout.hud.max.y <= layout.band);
        CHECK(layout.banner.max.y <= layout.band);
        for (const auto& file : levels) {
            const fluid::demo::Session session(file, 1);
            const PixelRect drawn = drawnBounds(session, session.camera(size));
            INFO(file.stem << " at " << size.x << "x" << size.y << ": the level's drawing spans x "
                           << drawn.min.x << ".." << drawn.max.x << ", y " << drawn.min.y << ".."
                           << drawn.max.y << " px; the band ends at y " << layout.band);
            // Below the band: neither the HUD nor the banner covers a wall's top.
            CHECK(drawn.min.y >= layout.band);
            // And whole in the window.
            CHECK(drawn.min.x >= 0.0f);
            CHECK(drawn.max.x <= float(size.x));
            CHECK(drawn.max.y <= float(size.y));
        }
    }
}

TEST_CASE("the layout: a 124 px band at 960 x 540 and up, scaled down in smaller windows",
          "[demo][layout]") {
    const OverlayLayout full = fluid::demo::overlayLayout({960, 540});
    CHECK(full.scale == 1.0f);
    CHECK(full.band == 124.0f);
    CHECK(full.hud.min == glm::vec2(10.0f, 10.0f));
    CHECK(full.hud.max.y == 118.0f);
    CHECK(fluid::demo::overlayLayout({1920, 1080}).band == 124.0f);
    const OverlayLayout half = fluid::demo::overlayLayout({480, 270});
    CHECK(half.scale == 0.5f);
    CHECK(half.band == 62.0f);
    CHECK(half.hud.max.x <= 0.45f * 480.0f + half.edge);
    // A camera frames [lo, hi] in the room below the band, centred there.
    const fluid::gl::Camera camera = fluid::demo::frameLevel({0.0f, 0.0f}, {1.0f, 1.0f}, {960, 540});
    const glm::vec2 top = camera.worldToPixel({0.5f, 1.0f});
    const glm::vec2 bottom = camera.worldToPixel({0.5f, 0.0f});
    CHECK(top.x == Approx(480.0f));
    CHECK(0.5f * (top.y + bottom.y) == Approx(124.0f + 0.5f * (540.0f - 124.0f)));
    CHECK(bottom.y - top.y == Approx((540.0f - 124.0f) / 1.1f));
}

TEST_CASE("the HUD's lines: modes on one line, the optional lines only when set",
          "[demo][layout]") {
    fluid::demo::HudInfo hud;
    hud.fps = 60.0f;
    hud.particles = 406;
    hud.simMsPerFrame = 0.8f;
    hud.substeps = 4;
    hud.view = "metaballs";
    hud.material = "water";
    auto joined = [](const std::vector<fluid::demo::HudSpan>& line) {
        std::string s;
        for (const auto& span : line) {
            s += (s.empty() ? "" : " ") + span.text;
        }
        return s;
    };
    auto lines = fluid::demo::hudLines(hud);
    REQUIRE(lines.size() == 4);
    CHECK(joined(lines[0]) == "60 fps | 406 particles");
    CHECK(joined(lines[1]) == "sim 0.8 ms/frame | 4 sub-steps");
    CHECK(joined(lines[2]) == "view metaballs   material water   gravity on");
    CHECK(joined(lines[3]) == "F1 help   Esc levels   Tab tuning");
    lines = fluid::demo::hudLines(fullHud());
    REQUIRE(lines.size() == 8);
    CHECK(joined(lines[2]) == "view metaballs   material yoghurt   gravity on");
    CHECK(joined(lines[3]) == "PAUSED P resume, . step");
    CHECK(joined(lines[4]) == "simulation behind: 71% speed (123 dropped)");
    CHECK(joined(lines[5]) == "cursor water, 3.6 cm deep, 507 Pa, 0.01 m/s");
    CHECK(joined(lines[6]) == "laser hits water at (0.32, 0.07) m, 0.41 m away");
    hud.zeroG = true;
    CHECK(joined(fluid::demo::hudLines(hud)[2]) == "view metaballs   material water   zero-g");
}

TEST_CASE("the HUD and the banner stay in their boxes in small windows", "[demo][layout]") {
    for (const glm::ivec2 size : {glm::ivec2{1280, 720}, glm::ivec2{960, 540},
                                  glm::ivec2{640, 360}, glm::ivec2{480, 270},
                                  glm::ivec2{320, 180}}) {
        INFO("window " << size.x << "x" << size.y);
        const OverlayLayout layout = fluid::demo::overlayLayout(size);
        ImGuiLayout imgui(size);
        // Every line of the HUD at once.
        float hudRight = 0.0f;
        const PixelRect hud = imgui.window("##hud", [&] {
            hudRight = fluid::demo::drawHud(fullHud(), layout.hud, layout.scale);
        });
        INFO("HUD " << hud.min.x << "," << hud.min.y << " .. " << hud.max.x << "," << hud.max.y
                    << " in the box .. " << layout.hud.max.x << "," << layout.hud.max.y);
        CHECK(inside(hud, layout.hud));
        CHECK(hudRight == Approx(hud.max.x).margin(1.0));
        // A goal and a long text: the title, what fits of the text, the progress bar.
        fluid::demo::BannerInfo banner;
        banner.name = "Cup and planks";
        banner.text = "Drag the planks with shift + mouse to guide the water into the cup: fill "
                      "it to 80% before the time runs out, and mind the splashes on the way";
        banner.state = fluid::GoalState::Pending;
        banner.goalValue = 0.3;
        banner.goalAmount = 0.8;
        banner.timeLimit = 60.0;
        const PixelRect drawn = imgui.window("##banner", [&] {
            const float right = fluid::demo::drawHud(fullHud(), layout.hud, layout.scale);
            fluid::demo::drawLevelBanner(banner, nullptr, layout, right);
        });
        INFO("banner " << drawn.min.x << "," << drawn.min.y << " .. " << drawn.max.x << ","
                       << drawn.max.y << ", the band ends at " << layout.band);
        CHECK(drawn.max.y <= layout.banner.max.y + 0.5f);
        CHECK(drawn.max.x <= float(size.x) - layout.edge + 0.5f);
        if (size.x >= 640) {
            CHECK(drawn.min.x >= hudRight); // beside the HUD, not over it
        }
    }
}
