// Property tests on every kernel in 2D and 3D (STYLE.md point 12):
// normalisation, non-negativity, derivative consistency, zero gradient sum
// on a lattice.
#include "sph/kernels.hpp"
#include "sph/lattice.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sph;

namespace {

// Integral of f(r) over the disc (2D) or ball (3D) of radius h: composite
// Simpson rule in r, many intervals (the kernels are smooth polynomials).
template <int D, class F>
Real radial_integral(F f, Real h) {
    const int intervals = 20000;
    const Real dr = h / intervals;
    auto g = [&](Real r) {
        const Real shell = D == 2 ? 2 * detail::pi * r : 4 * detail::pi * r * r;
        return f(r) * shell;
    };
    Real sum = g(0) + g(h);
    for (int k = 1; k < intervals; ++k)
        sum += (k % 2 ? 4 : 2) * g(k * dr);
    return sum * dr / 3;
}

template <int D, class Kernel>
void check_kernel_properties(Real h) {
    const Kernel kernel(h);
    // Normalisation: integral of W is 1.
    CHECK(radial_integral<D>([&](Real r) { return kernel.W(r); }, h) == Approx(1).epsilon(1e-6));
    // Non-negative inside, zero from h on.
    for (int k = 0; k <= 100; ++k) {
        const Real r = h * k / 100.0;
        CHECK(kernel.W(r) >= 0);
        CHECK(kernel.dW(r) <= 1e-12 / std::pow(h, D + 1));
    }
    CHECK(kernel.W(h) == 0);
    CHECK(kernel.W(1.5 * h) == 0);
    CHECK(kernel.dW(1.5 * h) == 0);
    // dW is the derivative of W (central differences).
    for (Real q : {0.1, 0.3, 0.45, 0.55, 0.7, 0.9}) {
        const Real r = q * h, e = 1e-6 * h;
        const Real numeric = (kernel.W(r + e) - kernel.W(r - e)) / (2 * e);
        CHECK(kernel.dW(r) == Approx(numeric).epsilon(1e-5));
    }
    // Gradient sums to zero over a symmetric lattice around a particle.
    const Real s = h / 2.3;
    Vec<D> sum(0);
    const int reach = 3;
    if constexpr (D == 2) {
        for (int i = -reach; i <= reach; ++i)
            for (int j = -reach; j <= reach; ++j)
                if (i || j) {
                    const Vec<D> x(i * s, j * s);
                    sum += kernel.grad(x, glm::length(x));
                }
    } else {
        for (int i = -reach; i <= reach; ++i)
            for (int j = -reach; j <= reach; ++j)
                for (int k = -reach; k <= reach; ++k)
                    if (i || j || k) {
                        const Vec<D> x(i * s, j * s, k * s);
                        sum += kernel.grad(x, glm::length(x));
                    }
    }
    const Real scale = std::abs(kernel.dW(0.5 * h));
    for (int a = 0; a < D; ++a)
        CHECK(std::abs(sum[a]) < 1e-12 * scale);
    // On a lattice, the kernel sum approximates 1 / s^D (partition of unity).
    const Real fine = h / 6;
    CHECK(lattice_kernel_sum<D>(kernel, fine) * std::pow(fine, D) == Approx(1).epsilon(0.02));
}

} // namespace

TEMPLATE_TEST_CASE("kernel properties in 2D", "[kernels]", Poly6<2>, Spiky<2>, CubicSpline<2>,
                   WendlandC2<2>) {
    for (Real h : {1.0, 0.01, 3.7e-3})
        check_kernel_properties<2, TestType>(h);
}

TEMPLATE_TEST_CASE("kernel properties in 3D", "[kernels]", Poly6<3>, Spiky<3>, CubicSpline<3>,
                   WendlandC2<3>) {
    for (Real h : {1.0, 0.01, 3.7e-3})
        check_kernel_properties<3, TestType>(h);
}

TEST_CASE("poly6 W_r2 equals W", "[kernels]") {
    const Poly6<2> k2(0.3);
    const Poly6<3> k3(0.3);
    for (Real r : {0.0, 0.05, 0.2, 0.29, 0.3, 0.5}) {
        CHECK(k2.W_r2(r * r) == Approx(k2.W(r)));
        CHECK(k3.W_r2(r * r) == Approx(k3.W(r)));
    }
}

// The float kernels' constants apart from their shapes (the single-precision
// cell passes multiply a sum by the constant once): their product is W and
// dW/dr / r, to float's rounding, at every r, 0 from r = h on.
TEMPLATE_TEST_CASE("float kernels: scale times shape is W and dW/dr / r", "[kernels]",
                   (CubicSpline<2, float>), (CubicSpline<3, float>), (WendlandC2<2, float>),
                   (WendlandC2<3, float>)) {
    for (const Real h : {1.0, 0.013}) {
        const TestType kernel(h);
        const float largest_W = kernel.W(0), largest_g = std::abs(kernel.dW_over_r(float(h / 2)));
        for (int i = 0; i <= 220; ++i) {
            const auto r = float(h * i / 200.0);
            INFO("h = " << h << ", r = " << r);
            CHECK(std::abs(kernel.W_scale() * kernel.W_shape(r) - kernel.W(r)) <=
                  2e-6f * largest_W);
            if (i > 0)
                CHECK(std::abs(kernel.dW_over_r_scale() * kernel.dW_over_r_shape(r) -
                               kernel.dW_over_r(r)) <=
                      2e-6f * std::abs(kernel.dW_over_r(r)) + 1e-7f * largest_g);
            if (r >= float(h)) {
                CHECK(kernel.W_shape(r) == 0);
                CHECK(kernel.dW_over_r_shape(r) == 0);
            }
        }
    }
}

TEST_CASE("the 2D constants are the seed's", "[kernels]") {
    const Real h = 0.7;
    // rho = 4 m / (pi h^8) sum (h^2 - r^2)^3
    CHECK(Poly6<2>(h).W(0.2) ==
          Approx(4 / (detail::pi * std::pow(h, 8)) * std::pow(h * h - 0.04, 3)));
    // The seed's pressure factor 15 (1-q)^2 / (pi h^4 q) |r_ij| is half the
    // spiky kernel's slope (the other half is the mean of two pressures).
    const Real r = 0.25, q = r / h;
    CHECK(-Spiky<2>(h).dW(r) / 2 ==
          Approx(15 * (1 - q) * (1 - q) / (detail::pi * std::pow(h, 4) * q) * r));
    CHECK(ViscosityLaplacian<2>(h).laplacian(r) ==
          Approx(40 * (1 - q) / (detail::pi * std::pow(h, 4))));
}

// The viscosity kernel is used through its Laplacian only. It is the
// Laplacian of a normalised kernel that vanishes with its slope at h, so
// integrating by parts against r^2 / (2 D) (whose Laplacian is 1) gives 1.
TEST_CASE("viscosity Laplacian is the Laplacian of a normalised kernel", "[kernels]") {
    for (Real h : {1.0, 0.02}) {
        const ViscosityLaplacian<2> l2(h);
        const ViscosityLaplacian<3> l3(h);
        CHECK(radial_integral<2>([&](Real r) { return l2.laplacian(r) * r * r / 4; }, h) ==
              Approx(1).epsilon(1e-6));
        CHECK(radial_integral<3>([&](Real r) { return l3.laplacian(r) * r * r / 6; }, h) ==
              Approx(1).epsilon(1e-6));
        CHECK(l2.laplacian(0.5 * h) > 0);
        CHECK(l2.laplacian(h) == 0);
    }
}
