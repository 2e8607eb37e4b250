// Kernels (fluid/src/kernels.h): normalisation over the plane, gradient antisymmetry and
// consistency, the viscosity Laplacian's 2D constant.
#include "kernels.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using fluid::test::kPi;

namespace {

// int_0^h 2 pi r f(r) dr by composite Simpson in double (f evaluated in float, as the solver does).
template <class F> double discIntegral(F&& f, double h, int intervals = 20000) {
    const double dr = h / intervals;
    double sum = 0.0;
    for (int k = 0; k <= intervals; ++k) {
        const double r = k * dr;
        const double w = (k == 0 || k == intervals) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
        sum += w * 2.0 * kPi * r * double(f(float(r)));
    }
    return sum * dr / 3.0;
}

} // namespace

TEST_CASE("wendland integrates to 1 over the disc", "[unit][kernels]") {
    for (const float h : {0.032f, 0.04f, 0.036f, 1.0f}) {
        CAPTURE(h);
        const double integral =
            discIntegral([h](float r) { return fluid::kernel::wendland(r, h); }, h);
        CHECK(integral == Approx(1.0).epsilon(0.005));
        // It is exactly normalised, so the quadrature should be far tighter than 0.5%.
        CHECK(integral == Approx(1.0).epsilon(1e-4));
        CHECK(fluid::kernel::wendland(h, h) == 0.0f);
        CHECK(fluid::kernel::wendland(1.5f * h, h) == 0.0f);
    }
}

TEST_CASE("wendland read on a square lattice sums to about 1", "[unit][kernels]") {
    // sum_j a W(|x_j|) over lattice points, spacing s (area a = s^2): the discrete
    // normalisation a resting preset block relies on.
    for (const auto& [h, s] : {std::pair{0.032f, 0.0100265f}, std::pair{0.04f, 0.0101543f}}) {
        CAPTURE(h, s);
        double sum = 0.0;
        const int n = int(std::ceil(h / s)) + 1;
        for (int i = -n; i <= n; ++i) {
            for (int j = -n; j <= n; ++j) {
                const float r = std::sqrt(float(i * i + j * j)) * s;
                sum += double(s) * s * fluid::kernel::wendland(r, h);
            }
        }
        CHECK(sum == Approx(1.0).epsilon(0.005));
    }
}

TEST_CASE("cohesion kernel integrates to 1 over the disc", "[unit][kernels]") {
    for (const float h : {0.032f, 0.04f}) {
        CAPTURE(h);
        const double integral =
            discIntegral([h](float r) { return fluid::kernel::cohesion(r, h); }, h);
        CHECK(integral == Approx(1.0).epsilon(0.005));
        CHECK(fluid::kernel::cohesion(h, h) == 0.0f);
        // Continuous at r = h/2, where Akinci's spline switches branch.
        const float a = fluid::kernel::cohesion(0.5f * h * (1.0f - 1e-5f), h);
        const float b = fluid::kernel::cohesion(0.5f * h * (1.0f + 1e-5f), h);
        CHECK(a == Approx(b).epsilon(1e-3));
    }
}

TEST_CASE("viscosity Laplacian has the 2D constant: int_0^h r^3 L dr = 2/pi", "[unit][kernels]") {
    for (const float h : {0.032f, 0.04f}) {
        CAPTURE(h);
        const int intervals = 20000;
        const double dr = double(h) / intervals;
        double sum = 0.0;
        for (int k = 0; k <= intervals; ++k) {
            const double r = k * dr;
            const double w = (k == 0 || k == intervals) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
            sum += w * r * r * r * fluid::kernel::viscosityLaplacian(float(r), h);
        }
        CHECK(sum * dr / 3.0 == Approx(2.0 / kPi).epsilon(0.005));
    }
}

TEST_CASE("viscosity Laplacian applied to v = x^2 on a fine lattice gives 2", "[unit][kernels]") {
    // sum_j V (v_j - v_i) L(|x_i - x_j|) approximates the Laplacian of v = x^2, which is 2.
    const float h = 0.032f;
    const double s = h / 80.0;
    const double xi = 0.3, yi = -0.1; // away from the origin: the linear part must cancel
    double sum = 0.0;
    const int n = 81;
    for (int a = -n; a <= n; ++a) {
        for (int b = -n; b <= n; ++b) {
            const double xj = xi + a * s, yj = yi + b * s;
            const float r = float(std::sqrt((xj - xi) * (xj - xi) + (yj - yi) * (yj - yi)));
            sum += s * s * (xj * xj - xi * xi) * fluid::kernel::viscosityLaplacian(r, h);
        }
    }
    CHECK(sum == Approx(2.0).epsilon(0.01));
}

TEST_CASE("kernel gradient is exactly antisymmetric", "[unit][kernels]") {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(-0.05f, 0.05f);
    std::uniform_real_distribution<float> base(-100.0f, 100.0f);
    const float h = 0.032f;
    int inside = 0;
    for (int k = 0; k < 20000; ++k) {
        const float xi = base(rng), yi = base(rng);
        const float xj = xi + u(rng), yj = yi + u(rng);
        // The solver's expression: grad W_ij = gradOverR(r) (x_i - x_j).
        const float dx = xi - xj, dy = yi - yj;
        const float r = std::sqrt(dx * dx + dy * dy);
        const float g = fluid::kernel::wendlandGradOverR(r, h);
        const float ex = xj - xi, ey = yj - yi;
        const float rr = std::sqrt(ex * ex + ey * ey);
        const float gg = fluid::kernel::wendlandGradOverR(rr, h);
        inside += r < h ? 1 : 0;
        REQUIRE(g * dx == -(gg * ex));
        REQUIRE(g * dy == -(gg * ey));
    }
    CHECK(inside > 1000); // the pairs did exercise the support
}

TEST_CASE("wendlandGradOverR is the derivative of wendland divided by r", "[unit][kernels]") {
    for (const float h : {0.032f, 0.04f}) {
        CAPTURE(h);
        const double peak = 140.0 / (kPi * double(h) * h * h * h) * h; // |dW/dr| scale
        for (int k = 1; k < 100; ++k) {
            const double r = h * k / 100.0;
            const double e = 1e-3 * h;
            const double fd = (double(fluid::kernel::wendland(float(r + e), h)) -
                               double(fluid::kernel::wendland(float(r - e), h))) /
                              (2.0 * e);
            const double analytic = r * double(fluid::kernel::wendlandGradOverR(float(r), h));
            CAPTURE(r, fd, analytic);
            CHECK(analytic == Approx(fd).margin(1e-3 * peak).epsilon(1e-3));
            CHECK(analytic <= 0.0); // W decreases outwards
        }
        // Finite at r = 0 (no division by r), and 0 beyond the support.
        CHECK(std::isfinite(fluid::kernel::wendlandGradOverR(0.0f, h)));
        CHECK(fluid::kernel::wendlandGradOverR(h, h) == 0.0f);
    }
}
