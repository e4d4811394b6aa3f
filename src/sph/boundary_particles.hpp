#pragma once
// Solid walls as particles (Akinci et al. 2012, "Versatile rigid-fluid coupling
// for incompressible SPH"): static particles sampled on the solid side of a
// wall, each with a volume V_b = 1 / sum_k W(x_b - x_k) over the boundary
// particles (eq. 4), so that an unevenly sampled wall still adds the right
// amount of "fluid" to the density of a particle beside it:
//   rho_i = sum_j m W_ij + sum_b rho0 V_b W_ib       (eq. 6)
// and pressure pushes a particle away from the wall as it would from fluid.
// Boundary particles never move; they live apart from the fluid State, with a
// grid of their own built once.

#include "sph/kernels.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/vec.hpp"

#include <span>
#include <vector>

namespace sph {

template <int D>
class BoundaryParticles {
  public:
    BoundaryParticles() = default;
    // Particles at `positions` sampling a surface, with Akinci's volumes from
    // a kernel of support radius h.
    BoundaryParticles(std::vector<Vec<D>> positions, Real h, KernelKind kernel);
    // Particles at `positions` that each fill the same volume.
    BoundaryParticles(std::vector<Vec<D>> positions, Real h, Real volume);
    // Particles at `positions`, each filling its own volume (volumes[b] for
    // positions[b]): domain walls and obstacles in one set (sph/obstacles.hpp).
    BoundaryParticles(std::vector<Vec<D>> positions, std::vector<Real> volumes, Real h);

    // The walls of `domain`: every lattice site (spacing s, aligned with the
    // fluid lattice that starts half a spacing inside the box) outside the box
    // and closer to it than the kernel's support h. A fluid particle at a wall
    // then sees a full lattice around it; each wall particle gets the volume a
    // fluid particle has on that lattice (its mass / rho0), so a fluid particle
    // at rest beside a wall has exactly the rest density. (Eq. 4's volumes are
    // for a single layer; on several full layers they would overcount.)
    static BoundaryParticles box_walls(const Box<D>& domain, Real spacing, Real h,
                                       Real lattice_volume);

    std::size_t size() const { return positions_.size(); }
    std::span<const Vec<D>> positions() const { return positions_; }
    std::span<const Real> volumes() const { return volumes_; }

    // For every point of `query`, the boundary particles closer than h
    // (strictly). Reuses the memory of `out`.
    void find_neighbours(std::span<const Vec<D>> query, NeighbourList& out) const;

  private:
    // Sorts the particles into the grid; where each of `positions` went.
    std::vector<std::uint32_t> build_grid(std::vector<Vec<D>> positions);
    using Cell = glm::vec<D, std::int64_t, glm::defaultp>;
    Cell cell_of(const Vec<D>& x) const;
    std::size_t cell_index(const Cell& c) const;
    template <class Visit>
    void for_each_near(const Vec<D>& x, Visit&& visit) const;

    std::vector<Vec<D>> positions_; // sorted by cell
    std::vector<Real> volumes_;     // m^3 (m^2 in 2D)
    Real h_ = 0;
    // Dense grid of cells of size h over the particles' bounding box;
    // cell_start_[c] .. cell_start_[c + 1] are the particles in cell c.
    Vec<D> origin_{0};
    Cell cells_{0};
    std::vector<std::uint32_t> cell_start_;
};

} // namespace sph
