// fluid::box2d's sinf, cosf and atan2f (plugins/box2d/src/box2d_math.cpp): what Box2D turns its
// bodies with, the same bits on every platform, within one unit in the last place of the
// exact value (the C library's double functions, rounded to float, stand for it here).
#include "../../plugins/box2d/src/box2d_math.h"

#include <box2d/box2d.h>
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace {

namespace m = fluid::box2d::detail;

uint32_t bits(float x) {
    uint32_t b = 0;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

// Units in the last place between two finite floats of the same sign (or both near 0).
int64_t ulps(float a, float b) {
    const auto ordered = [](float x) {
        const int64_t i = int32_t(bits(x));
        return i < 0 ? int64_t(INT32_MIN) - i : i;
    };
    return std::llabs(ordered(a) - ordered(b));
}

} // namespace

TEST_CASE("box2d math: sin and cos within one ulp of the exact value, the same at every angle "
          "a body takes",
          "[box2d][math]") {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> angle(-50.0f, 50.0f);
    int64_t worst = 0;
    uint32_t differ = 0;
    const uint32_t count = 2'000'000;
    for (uint32_t i = 0; i < count; ++i) {
        const float x = i < 1000 ? float(i) * 0.01f - 5.0f : angle(random);
        const float s = m::sin(x), c = m::cos(x);
        const float es = float(std::sin(double(x))), ec = float(std::cos(double(x)));
        worst = std::max({worst, ulps(s, es), ulps(c, ec)});
        differ += (bits(s) != bits(es)) + (bits(c) != bits(ec));
    }
    std::printf("[measure] box2d math: sin and cos of %u angles in [-50, 50] rad: %u of %u "
                "results differ from the C library's rounded double, by at most %lld ulp\n",
                count, differ, 2 * count, static_cast<long long>(worst));
    CHECK(worst <= 1);
    CHECK(differ < count / 1000);
    // Exact where the value is.
    CHECK(bits(m::sin(0.0f)) == bits(0.0f));
    CHECK(bits(m::sin(-0.0f)) == bits(-0.0f));
    CHECK(m::cos(0.0f) == 1.0f);
    CHECK(std::isnan(m::sin(std::numeric_limits<float>::infinity())));
    CHECK(std::isnan(m::cos(-std::numeric_limits<float>::infinity())));
    CHECK(std::isnan(m::sin(std::numeric_limits<float>::quiet_NaN())));
    // Far out still finite and in [-1, 1].
    for (const float x : {1e7f, -3e12f, 3e38f}) {
        CHECK(std::fabs(m::sin(x)) <= 1.0f);
        CHECK(std::fabs(m::cos(x)) <= 1.0f);
    }
}

TEST_CASE("box2d math: the coupling's double sin and cos within two ulp of the exact value",
          "[box2d][math]") {
    // The reference: the C library's long double functions (x87's 64-bit significand here),
    // rounded to double.
    const auto ulpsDouble = [](double a, double b) {
        const auto ordered = [](double x) {
            int64_t i = 0;
            std::memcpy(&i, &x, sizeof i);
            return i < 0 ? INT64_MIN - i : i;
        };
        const int64_t d = ordered(a) - ordered(b);
        return d < 0 ? -d : d;
    };
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> angle(-1000.0, 1000.0);
    int64_t worst = 0;
    for (uint32_t i = 0; i < 1'000'000; ++i) {
        const double x = i < 1000 ? double(i) * 0.01 - 5.0 : angle(random);
        worst = std::max({worst, ulpsDouble(m::sin(x), double(std::sin(static_cast<long double>(x)))),
                          ulpsDouble(m::cos(x), double(std::cos(static_cast<long double>(x))))});
    }
    std::printf("[measure] box2d math: double sin and cos of a million angles in [-1000, 1000] "
                "rad: at most %lld ulp from the C library's long double\n",
                static_cast<long long>(worst));
    CHECK(worst <= 2);
    CHECK(std::bit_cast<uint64_t>(m::sin(-0.0)) == std::bit_cast<uint64_t>(-0.0));
    CHECK(m::cos(0.0) == 1.0);
    CHECK(std::isnan(m::sin(std::numeric_limits<double>::infinity())));
    CHECK(std::isnan(m::cos(std::numeric_limits<double>::quiet_NaN())));
    for (const double x : {1e7, -3e12, 1e300}) {
        CHECK(std::fabs(m::sin(x)) <= 1.0);
        CHECK(std::fabs(m::cos(x)) <= 1.0);
    }
}

TEST_CASE("box2d math: atan2 within one ulp, with the C standard's zeros and infinities",
          "[box2d][math]") {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> value(-3.0f, 3.0f);
    int64_t worst = 0;
    for (uint32_t i = 0; i < 1'000'000; ++i) {
        const float y = value(random), x = value(random);
        worst = std::max(worst, ulps(m::atan2(y, x), float(std::atan2(double(y), double(x)))));
    }
    std::printf("[measure] box2d math: atan2 of a million points in [-3, 3]^2: at most %lld ulp "
                "from the C library's rounded double\n",
                static_cast<long long>(worst));
    CHECK(worst <= 1);
    const float inf = std::numeric_limits<float>::infinity();
    const float pi = float(3.14159265358979323846);
    CHECK(bits(m::atan2(0.0f, 1.0f)) == bits(0.0f));
    CHECK(bits(m::atan2(-0.0f, 1.0f)) == bits(-0.0f));
    CHECK(m::atan2(0.0f, -1.0f) == pi);
    CHECK(m::atan2(-0.0f, -1.0f) == -pi);
    CHECK(m::atan2(1.0f, 0.0f) == float(1.57079632679489661923));
    CHECK(m::atan2(-1.0f, inf) == -0.0f);
    CHECK(m::atan2(1.0f, -inf) == pi);
    CHECK(m::atan2(inf, inf) == float(0.785398163397448309616));
    CHECK(std::isnan(m::atan2(std::numeric_limits<float>::quiet_NaN(), 1.0f)));
}

TEST_CASE("box2d math: Box2D turns its bodies with fluid::box2d's sinf and cosf",
          "[box2d][math]") {
    // b2Body's constructor, in the Box2D library (Debian's shared one natively), turns the
    // body by its angle: with the C library's sinf, cosf or sincosf it would read their bits.
    b2World world(b2Vec2(0.0f, 0.0f));
    std::mt19937 random(3);
    std::uniform_real_distribution<float> angle(-7.0f, 7.0f);
    // The first three: angles where glibc's sinf on this project's machines rounds 1 ulp away
    // from the exact value (docs/box2d.md, "The same bits everywhere"): a Box2D reading the C
    // library's would fail here.
    const float rounded[] = {0x1.4802fcp-7f, 0x1.4802fep-7f, 0x1.489ea2p-7f};
    for (int i = 0; i < 1003; ++i) {
        b2BodyDef def;
        def.angle = i < 3 ? rounded[i] : angle(random);
        const b2Body* body = world.CreateBody(&def);
        REQUIRE(bits(body->GetTransform().q.s) == bits(m::sin(def.angle)));
        REQUIRE(bits(body->GetTransform().q.c) == bits(m::cos(def.angle)));
    }
}
