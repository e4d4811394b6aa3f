#pragma once
// Smoothing kernels, each written for 2D and 3D with its proper normalisation.
// Convention throughout sphclip: `h` is the support radius (the seed's
// interaction radius): W(r) = 0 for r >= h.
//
// Interface shared by every kernel (tests/test_kernels.cpp checks it):
//   W(r)        value at distance r
//   dW(r)       radial derivative dW/dr (<= 0 inside the support)
//   dW_over_r(r) dW/dr / r, for r > 0: the gradient is dW_over_r(r) x. Written
//               without a division where the kernel allows (every kernel but
//               spiky), since divisions bound the force loops' speed
//   grad(x, r)  gradient of W at offset x with |x| = r > 0
//   smooth_at_origin  whether dW_over_r is finite at r = 0, so the gradient
//               dW_over_r(r) x is continuous there (and 0 at r = 0): no case
//               for coincident particles is needed (every kernel but spiky)
// Kernels store 1/h, and scale by it rather than dividing by h, for the same
// reason.

#include "sph/vec.hpp"

#include <array>
#include <concepts>
#include <numbers>
#include <string_view>
#include <type_traits>

namespace sph {

namespace detail {
constexpr Real pi = std::numbers::pi_v<Real>;
template <std::floating_point T>
T cube(T x) {
    return x * x * x;
}
// x^N as the loop y = 1; y *= x (N times) would give it, with the exponent
// fixed at compile time: straight-line code, which a vectorised loop may
// call (a loop inside keeps the caller's loop scalar).
template <int N, std::floating_point T>
T pow_int(T x) {
    if constexpr (N == 0)
        return 1;
    else
        return pow_int<N - 1>(x) * x;
}
// A kernel's value at one r from its form for each lane of a vector,
// each(r, out).
template <std::floating_point T, class Each>
T one_lane(T r, const Each& each) {
    T out;
    each(r, out);
    return out;
}
} // namespace detail

// Müller, Charypar & Gross 2003, "Particle-based fluid simulation for
// interactive applications", eq. 20: poly6 = C (h^2 - r^2)^3.
// 2D: C = 4 / (pi h^8)  (the seed's density constant);
// 3D: C = 315 / (64 pi h^9).
// Both follow from integral of W over the disc / ball being 1.
template <int D>
struct Poly6 {
    static constexpr bool smooth_at_origin = true;
    Real h, h2, norm;
    explicit Poly6(Real support)
        : h(support), h2(support * support),
          norm(D == 2 ? 4 / (detail::pi * detail::pow_int<8>(support))
                      : 315 / (64 * detail::pi * detail::pow_int<9>(support))) {}
    // Value from the squared distance: no square root in the density loop.
    Real W_r2(Real r2) const { return r2 < h2 ? norm * detail::cube(h2 - r2) : 0; }
    Real W(Real r) const { return W_r2(r * r); }
    Real dW(Real r) const { return r * dW_over_r(r); }
    Real dW_over_r(Real r) const { return r < h ? -6 * norm * (h2 - r * r) * (h2 - r * r) : 0; }
    Vec<D> grad(const Vec<D>& x, Real r) const { return dW_over_r(r) * x; }
};

// Müller et al. 2003, eq. 21: spiky = C (h - r)^3, whose gradient does not vanish
// at r = 0, so close particles still repel.
// 2D: C = 10 / (pi h^5); 3D: C = 15 / (pi h^6).
template <int D>
struct Spiky {
    static constexpr bool smooth_at_origin = false;
    Real h, norm;
    explicit Spiky(Real support)
        : h(support), norm(D == 2 ? 10 / (detail::pi * detail::pow_int<5>(support))
                                  : 15 / (detail::pi * detail::pow_int<6>(support))) {}
    Real W(Real r) const { return r < h ? norm * detail::cube(h - r) : 0; }
    Real dW(Real r) const { return r < h ? -3 * norm * (h - r) * (h - r) : 0; }
    Real dW_over_r(Real r) const { return dW(r) / r; }
    Vec<D> grad(const Vec<D>& x, Real r) const { return dW_over_r(r) * x; }
};

// Müller et al. 2003, eq. 22: the viscosity kernel is used only through its
// Laplacian, lap W = C (h - r).
// 3D: C = 45 / (pi h^6) (Müller); 2D: C = 40 / (pi h^5) (the seed's constant).
// Both are the Laplacian of a normalised kernel that vanishes with its slope at
// r = h, so integral of lapW * r^2 / (2 D) over the support is 1 (the property
// the tests check).
template <int D>
struct ViscosityLaplacian {
    Real h, norm;
    explicit ViscosityLaplacian(Real support)
        : h(support), norm(D == 2 ? 40 / (detail::pi * detail::pow_int<5>(support))
                                  : 45 / (detail::pi * detail::pow_int<6>(support))) {}
    Real laplacian(Real r) const { return r < h ? norm * (h - r) : 0; }
};

// Cubic B-spline (Monaghan 1992, M4), written with support radius h
// (as in SPlisHSPlasH's CubicKernel): q = r / h,
//   W = C (6 (q^3 - q^2) + 1)  for q <= 1/2,   W = C 2 (1 - q)^3  for q <= 1,
// 2D: C = 40 / (7 pi h^2); 3D: C = 8 / (pi h^3).
// T = float is the kernel of the single-precision passes
// (sph/single_precision/): the same formulas, with constants rounded from
// double. (Converting double members inside a loop keeps GCC from
// vectorising it, so the float kernel holds float constants.)
template <int D, std::floating_point T = Real>
struct CubicSpline {
    static constexpr bool smooth_at_origin = true;
    using Single = CubicSpline<D, float>;
    T h, inverse_h, norm;
    explicit CubicSpline(Real support)
        : h(T(support)), inverse_h(T(1 / support)),
          norm(T(D == 2 ? 40 / (7 * detail::pi * support * support)
                        : 8 / (detail::pi * detail::cube(support)))) {}
    T W(T r) const {
        return detail::one_lane(r, [this](const T& x, T& w) { W_each(x, w); });
    }
    T dW(T r) const {
        return detail::one_lane(r, [this](const T& x, T& d) { dW_each(x, d); });
    }
    T dW_over_r(T r) const {
        return detail::one_lane(r, [this](const T& x, T& d) { dW_over_r_each(x, d); });
    }
    // The same for one T or for each lane of a GCC vector of T at once
    // (dfsph's pass over a slice), into `out`: selects, not branches; a
    // scalar still computes only the branch it takes. (A wide vector
    // returned by value changes the ABI in a build without AVX.)
    template <class V>
    void W_each(const V& r, V& out) const {
        const V q = r * inverse_h;
        const V a = 1 - q; // a a a is detail::cube(a), written out for a vector
        out = q >= 1
                  ? V{}
                  : (q <= T(0.5) ? norm * (6 * (q * q * q - q * q) + 1) : norm * 2 * (a * a * a));
    }
    template <class V>
    void dW_each(const V& r, V& out) const {
        const V q = r * inverse_h;
        out = q >= 1 ? V{}
                     : (q <= T(0.5) ? norm * 6 * (3 * q * q - 2 * q) * inverse_h
                                    : -norm * 6 * (1 - q) * (1 - q) * inverse_h);
    }
    // q / r = 1 / h: the inner part is 6 (3 q - 2) / h^2, the outer part
    // still needs 1 / r.
    template <class V>
    void dW_over_r_each(const V& r, V& out) const {
        const V q = r * inverse_h;
        V outer;
        dW_each(r, outer);
        out = q >= 1 ? V{}
                     : (q <= T(0.5) ? norm * 6 * (3 * q - 2) * inverse_h * inverse_h : outer / r);
    }
    // W = W_scale() W_shape(r) and dW_over_r = dW_over_r_scale()
    // dW_over_r_shape(r) (in float the products round otherwise): a pass
    // summing terms linear in W or in the gradient multiplies by the
    // constant once, after the sum (the single-precision cell passes).
    T W_scale() const { return norm; }
    T W_shape(T r) const {
        const T q = r * inverse_h;
        const T a = 1 - q;
        return q >= 1 ? T(0) : (q <= T(0.5) ? 6 * (q * q * q - q * q) + 1 : 2 * (a * a * a));
    }
    T dW_over_r_scale() const { return norm * 6 * inverse_h; }
    T dW_over_r_shape(T r) const {
        const T q = r * inverse_h;
        const T a = 1 - q;
        return q >= 1 ? T(0) : (q <= T(0.5) ? (3 * q - 2) * inverse_h : -(a * a) / r);
    }
    Vec<D> grad(const Vec<D>& x, Real r) const { return Real(dW_over_r(T(r))) * x; }
};

// Wendland C2 (Wendland 1995; Dehnen & Aly 2012, table 1), support radius h:
//   W = C (1 - q)^4 (1 + 4 q),   2D: C = 7 / (pi h^2);  3D: C = 21 / (2 pi h^3).
// T = float: as for CubicSpline.
template <int D, std::floating_point T = Real>
struct WendlandC2 {
    static constexpr bool smooth_at_origin = true;
    using Single = WendlandC2<D, float>;
    T h, inverse_h, norm;
    explicit WendlandC2(Real support)
        : h(T(support)), inverse_h(T(1 / support)),
          norm(T(D == 2 ? 7 / (detail::pi * support * support)
                        : 21 / (2 * detail::pi * detail::cube(support)))) {}
    T W(T r) const {
        return detail::one_lane(r, [this](const T& x, T& w) { W_each(x, w); });
    }
    // d/dr of (1-q)^4 (1+4q) = -20 q (1-q)^3 / h
    T dW(T r) const { return r * dW_over_r(r); }
    T dW_over_r(T r) const {
        return detail::one_lane(r, [this](const T& x, T& d) { dW_over_r_each(x, d); });
    }
    // For one T or each lane of a vector of T, as in CubicSpline.
    template <class V>
    void W_each(const V& r, V& out) const {
        const V q = r * inverse_h;
        const V a = 1 - q; // ((a a) a) a is detail::pow_int<4>(a), written out for a vector
        out = q < 1 ? norm * (a * a * a * a) * (1 + 4 * q) : V{};
    }
    // q / r = 1 / h: no division at all.
    template <class V>
    void dW_over_r_each(const V& r, V& out) const {
        const V q = r * inverse_h;
        const V a = 1 - q;
        out = q < 1 ? -20 * norm * inverse_h * inverse_h * (a * a * a) : V{};
    }
    // The constants apart, as in CubicSpline.
    T W_scale() const { return norm; }
    T W_shape(T r) const {
        const T q = r * inverse_h;
        const T a = 1 - q;
        return q < 1 ? (a * a * a * a) * (1 + 4 * q) : T(0);
    }
    T dW_over_r_scale() const { return -20 * norm * inverse_h * inverse_h; }
    T dW_over_r_shape(T r) const {
        const T q = r * inverse_h;
        const T a = 1 - q;
        return q < 1 ? a * a * a : T(0);
    }
    Vec<D> grad(const Vec<D>& x, Real r) const { return Real(dW_over_r(T(r))) * x; }
};

// The seed's pair of kernels as one kernel: poly6 values for the density,
// spiky gradients for the forces (Müller et al. 2003, sec. 3.5). Its gradient
// is not the gradient of its value; the seed chose them for what each does
// best (poly6 needs no square root, spiky keeps repelling at r -> 0).
template <int D>
struct SeedKernel {
    static constexpr bool smooth_at_origin = false;
    Poly6<D> value;
    Spiky<D> gradient;
    Real h;
    explicit SeedKernel(Real support) : value(support), gradient(support), h(support) {}
    Real W_r2(Real r2) const { return value.W_r2(r2); }
    Real W(Real r) const { return value.W(r); }
    Real dW(Real r) const { return gradient.dW(r); }
    Real dW_over_r(Real r) const { return gradient.dW_over_r(r); }
    Vec<D> grad(const Vec<D>& x, Real r) const { return gradient.grad(x, r); }
};

// Kernels a scene can choose (`solver.kernel`).
enum class KernelKind { seed, cubic_spline, wendland_c2 };
// Their names in scenes, in the enum's order.
inline constexpr std::array<std::string_view, 3> kernel_kind_names{"seed", "cubic_spline",
                                                                   "wendland_c2"};

// Calls f with a default-constructed kernel object of the chosen kind, so a
// caller instantiates its loops once per kernel type and picks at run time.
template <int D, class F>
decltype(auto) with_kernel(KernelKind kind, Real support, F&& f) {
    switch (kind) {
    case KernelKind::cubic_spline:
        return f(CubicSpline<D>(support));
    case KernelKind::wendland_c2:
        return f(WendlandC2<D>(support));
    case KernelKind::seed:
        break;
    }
    return f(SeedKernel<D>(support));
}

// Whether the kernel's gradient / r is finite at r = 0 (Kernel::smooth_at_origin).
inline bool smooth_at_origin(KernelKind kind) {
    return with_kernel<2>(kind, 1, [](const auto& kernel) {
        return std::decay_t<decltype(kernel)>::smooth_at_origin;
    });
}

} // namespace sph
