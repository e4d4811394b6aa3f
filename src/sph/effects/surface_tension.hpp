#pragma once
// Surface tension after Akinci, Akinci & Teschner 2013, "Versatile surface
// tension and adhesion for SPH fluids" (sec. 4). Two pair forces, with
// gamma the scene's coefficient:
//   cohesion   F_ij = -gamma m_i m_j C(r) x_ij / r              (eq. 1)
//   curvature  F_ij = -gamma m_i (n_i - n_j)                    (eq. 4)
// with the surface normal n_i = h sum_j m_j / rho_j grad W_ij (eq. 3, h the
// support radius), which is non-zero only near the surface, so the second
// term pulls surface particles toward smaller curvature. Both are scaled by
// K_ij = 2 rho0 / (rho_i + rho_j) (eq. 5), which strengthens them where a
// particle lacks neighbours. The cohesion spline C(r) (eq. 2) attracts at
// long range and repels at short range, so the fluid holds together without
// clumping. A drop left alone becomes round.
// The normals are this effect's own array: they exist only when a scene names
// surface tension.

#include "sph/effects/effect.hpp"
#include "sph/kernels.hpp"
#include "sph/pair_direction.hpp"

#include <cmath>

namespace sph {

// The scene's `effects.surface_tension`.
struct SurfaceTensionSettings {
    static constexpr const char* key = "surface_tension"; // in the scene's `effects`
    double gamma = 1.0; // the coefficient of cohesion and curvature
    EffectCapabilities capabilities() const { return {.reads_neighbour_lists = true}; }
    // How the scene's checks name it.
    std::string label() const { return "effects.surface_tension"; }
};

inline const KeyTable<SurfaceTensionSettings>& surface_tension_keys() {
    static const KeyTable<SurfaceTensionSettings> keys{
        {.path = "gamma",
         .field = &SurfaceTensionSettings::gamma,
         .doc = "Surface tension effect (Akinci et al. 2013: cohesion and curvature), its "
                "coefficient gamma; a drop in zero gravity becomes round. Absent: no surface "
                "tension.",
         .bound = Bound::positive},
    };
    return keys;
}

// Akinci et al. 2013, eq. 2, support radius h:
//   C(r) = k (h - r)^3 r^3                 for h/2 < r <= h
//   C(r) = k (2 (h - r)^3 r^3 - h^6 / 64)  for 0 < r <= h/2
// 3D: k = 32 / (pi h^9) (the paper's); 2D: k = 40.32 / (pi h^8), which gives
// C the same integral over the plane as the 3D one over space.
template <int D>
struct CohesionSpline {
    Real h, k;
    explicit CohesionSpline(Real support)
        : h(support), k(D == 3 ? 32 / (detail::pi * std::pow(support, 9))
                               : Real(40.319) / (detail::pi * std::pow(support, 8))) {}
    Real operator()(Real r) const {
        if (r > h || r <= 0)
            return 0;
        const Real a = detail::cube(h - r) * detail::cube(r);
        return 2 * r > h ? k * a : k * (2 * a - std::pow(h, 6) / 64);
    }
};

template <int D>
class SurfaceTension final : public Effect<D> {
  public:
    explicit SurfaceTension(Real gamma) : gamma_(gamma) {}
    std::string_view name() const override { return "surface_tension"; }
    Real coefficient() const { return gamma_; }

    void apply(const Params<D>& params, const EffectInputs<D>& in, State<D>& state) override {
        const NeighbourList& neighbours = in.neighbours;
        with_kernel<D>(params.kernel, params.h, [&](const auto& kernel) {
            compute_normals(params, kernel, neighbours, state);
        });
        const CohesionSpline<D> C(params.h);
        const std::size_t n = state.size();
        const Real m = params.mass, rho0 = params.rest_density;
        // Gather: each particle sums its own side of every pair.
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D> a(0);
            for (std::uint32_t j : neighbours.of(i)) {
                const Vec<D> x_ij = state.position[i] - state.position[j];
                const Real r = std::sqrt(squared_length<D>(x_ij));
                const Vec<D> direction = pair_direction(state, i, j, x_ij, r, params.h);
                const Vec<D> cohesion = m * C(r) * direction;
                const Vec<D> curvature = normals_[i] - normals_[j];
                const Real K = 2 * rho0 / (state.density[i] + state.density[j]);
                a -= gamma_ * K * (cohesion + curvature);
            }
            state.acceleration[i] += a;
        }
    }

    std::size_t bytes() const override {
        return normals_.capacity() * sizeof(Vec<D>);
    }

  private:
    template <class Kernel>
    void compute_normals(const Params<D>& params, const Kernel& kernel,
                         const NeighbourList& neighbours, const State<D>& state) {
        const std::size_t n = state.size();
        normals_.resize(n);
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D> sum(0);
            for (std::uint32_t j : neighbours.of(i)) {
                const Vec<D> x_ij = state.position[i] - state.position[j];
                const Real r = std::sqrt(squared_length<D>(x_ij));
                if (r > 0)
                    sum += (params.mass / state.density[j]) * kernel.grad(x_ij, r);
            }
            normals_[i] = params.h * sum;
        }
    }

    Real gamma_;
    std::vector<Vec<D>> normals_; // n_i, m (dimensionless in units of h)
};

template <int D>
std::unique_ptr<Effect<D>> make_effect(const SurfaceTensionSettings& s) {
    return std::make_unique<SurfaceTension<D>>(s.gamma);
}

} // namespace sph
