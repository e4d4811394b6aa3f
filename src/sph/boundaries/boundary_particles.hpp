#pragma once
// Solid walls as particles (Akinci et al. 2012, "Versatile rigid-fluid coupling
// for incompressible SPH"): static particles sampled on the solid side of a
// wall, each with a volume V_b = 1 / sum_k W(x_b - x_k) over the boundary
// particles (eq. 4), so that an unevenly sampled wall still adds the right
// amount of "fluid" to the density of a particle beside it:
//   rho_i = sum_j m W_ij + sum_b rho0 V_b W_ib       (eq. 6)
// and pressure pushes a particle away from the wall as it would from fluid.
// They live apart from the fluid State, with a grid of their own built once.
// Paddles (sph/boundaries/paddles.hpp) add particles that move: they come after the
// static ones, with velocities and a second grid rebuilt whenever they move,
// so the static grid, and every sum over static particles, stays as it is.

#include "sph/kernels.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/select_in_order.hpp"
#include "sph/vec.hpp"

#include <array>
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
    // positions[b]): domain walls and obstacles in one set (sph/boundaries/obstacles.hpp).
    BoundaryParticles(std::vector<Vec<D>> positions, std::vector<Real> volumes, Real h);
    // The same for some of a set's particles (those a process needs over MPI
    // ranks, in the set's order) whose bounding box is `whole`: their grid
    // is the whole set's, so each query finds the same particles in the same
    // order where these include every one within h of it.
    BoundaryParticles(std::vector<Vec<D>> positions, std::vector<Real> volumes, Real h,
                      const Box<D>& whole);

    // The sites of box_walls (in its order) that lie inside `region` (all
    // of them without one); `bounds` is set to the box of all of them.
    static std::vector<Vec<D>> box_wall_sites(const Box<D>& domain, Real spacing, Real h,
                                              const Box<D>* region, Box<D>& bounds);

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
    // The bounding box of the static particles of the whole set (of which
    // this may hold some); empty (min > max) when there are none.
    const Box<D>& static_bounds() const { return bounds_; }
    // Replaces the static particles with `other`'s (a set without moving
    // ones), keeping the moving ones as they are now.
    void replace_static(BoundaryParticles&& other);
    std::span<const Vec<D>> positions() const { return positions_; }
    std::span<const Real> volumes() const { return volumes_; }

    // For every point of `query`, the boundary particles closer than h
    // (strictly): the static ones first, then the moving ones. Reuses the
    // memory of `out`.
    void find_neighbours(std::span<const Vec<D>> query, NeighbourList& out) const;

    // Adds particles that move (a paddle's shell), after the static ones:
    // particle moving_begin() + k is at rest at rest[k], fills volumes[k] and
    // belongs to group[k] (its paddle). They start at rest, at zero velocity.
    void add_moving(std::vector<Vec<D>> rest, std::vector<Real> volumes,
                    std::vector<std::uint32_t> group);
    // The first moving particle; size() when none moves.
    std::size_t moving_begin() const { return moving_begin_; }
    bool has_moving() const { return moving_begin_ < positions_.size(); }
    std::span<const Vec<D>> rest_positions() const { return rest_; }
    std::span<const std::uint32_t> groups() const { return group_; }
    // The moving particles' positions and velocities, in add_moving's order,
    // to be set by their motion; refresh_moving_grid() after moving them.
    std::span<Vec<D>> moving_positions() {
        return std::span<Vec<D>>(positions_).subspan(moving_begin_);
    }
    std::span<Vec<D>> moving_velocities() {
        return std::span<Vec<D>>(velocities_).subspan(moving_begin_);
    }
    void refresh_moving_grid();
    // Appends to `out`, in increasing order, every particle inside `box`
    // (its faces included): the static ones through their grid, reading
    // only the cells the box overlaps, then the moving ones.
    void within(const Box<D>& box, std::vector<std::uint32_t>& out) const;
    // Velocity of particle b (m/s): exactly 0 for a static one.
    // (Stored for the static ones too: a plain load keeps the loops that
    // read it vectorised.)
    Vec<D> velocity(std::uint32_t b) const { return velocities_[b]; }
    std::span<const Vec<D>> velocities() const { return velocities_; }

  private:
    using Cell = glm::vec<D, std::int64_t, glm::defaultp>;
    // Dense grid of cells of size h over some particles' bounding box;
    // entries cell_start[c] .. cell_start[c + 1] are the particles in cell c.
    struct Grid {
        Vec<D> origin{0};
        Cell first{0}; // the first cell held, on the grid from `origin`
        Cell cells{0};
        std::vector<std::uint32_t> cell_start;
        // Per cell, whether it or a cell beside it holds a particle (the
        // static grid only): most fluid particles are far from every wall,
        // and one look here spares them 3^D empty cells.
        std::vector<std::uint8_t> near_any;
    };
    // Sorts the particles into the static grid, laid from the corner of
    // `whole` (their own box when null); where each of `positions` went.
    std::vector<std::uint32_t> build_grid(std::vector<Vec<D>> positions,
                                          const Box<D>* whole = nullptr);
    // The static particles at `positions`, each filling volumes[b], on the
    // grid of `whole` (their own box when null).
    void take_static(std::vector<Vec<D>> positions, std::vector<Real> volumes, const Box<D>* whole);
    // Fills grid.near_any from its cells' particles.
    static void mark_near_cells(Grid& grid);
    // Lays `grid` over the bounding box of `points` (not empty); the cell count.
    std::size_t fit_grid(Grid& grid, std::span<const Vec<D>> points) const;
    Cell cell_of(const Grid& grid, const Vec<D>& x) const;
    static std::size_t cell_index(const Grid& grid, const Cell& c);
    template <class Visit>
    void for_each_near(const Vec<D>& x, Visit&& visit) const;
    // The particles of `grid` near x; an entry e is particle e (the static
    // grid) or moving_order_[e] (the moving one).
    template <bool Moving, class Visit>
    void for_each_in(const Grid& grid, const Vec<D>& x, Visit&& visit) const;
    // The same, writing the near ones to out[count...] (growing it, never
    // shrinking it); returns the new count.
    template <bool Moving>
    std::size_t collect_in(const Grid& grid, const Vec<D>& x, std::vector<std::uint32_t>& out,
                           std::size_t count) const;
    // collect_in for the static grid, each row of cells through the
    // vectorised distance filter (sph/neighbours/distance_filter.hpp);
    // distance2 is its scratch.
    std::size_t collect_static(const Vec<D>& x, std::vector<std::uint32_t>& out,
                               std::vector<Real>& distance2, std::size_t count) const;
    // visit_row(begin, end) for each row of 3 (or fewer) cells along x
    // around x's cell: the entries begin..end of `grid`.
    template <class VisitRow>
    void for_each_row_in(const Grid& grid, const Vec<D>& x, VisitRow&& visit_row) const;
    // The same for the rows of the cells lo..hi (inside the grid), x along
    // each row, in cell_index's order.
    template <class VisitRow>
    static void for_each_row_between(const Grid& grid, const Cell& lo, const Cell& hi,
                                     VisitRow&& visit_row);

    std::vector<Vec<D>> positions_; // static ones sorted by cell, then moving ones
    std::vector<Real> volumes_;     // m^3 (m^2 in 2D)
    Real h_ = 0;
    Grid grid_; // the static particles, built once
    // The static particles' positions by component, and their indices, as
    // the distance filter reads them.
    std::array<std::vector<Real>, D> static_x_;
    std::vector<std::uint32_t> static_index_;
    Box<D> bounds_{Vec<D>(1), Vec<D>(0)}; // the whole static set's box
    std::vector<Vec<D>> velocities_;      // m/s, 0 for the static ones
    // Moving particles: where they are at rest, their group, and their own
    // grid, its entries indices into positions_.
    std::size_t moving_begin_ = 0;
    std::vector<Vec<D>> rest_;
    std::vector<std::uint32_t> group_;
    Grid moving_grid_;
    std::vector<std::uint32_t> moving_order_;
    std::vector<std::size_t> moving_cell_;   // scratch of refresh_moving_grid()
    std::vector<std::uint32_t> moving_next_; // scratch of refresh_moving_grid()
    // Scratch of find_neighbours(): a block of query rows' walls each, as
    // much memory as the lists it fills (it runs one call at a time).
    mutable std::vector<std::vector<std::uint32_t>> block_rows_;
    mutable std::vector<std::size_t> block_counts_;          // entries of block_rows_ in use
    mutable std::vector<std::vector<Real>> block_distance2_; // collect_static's scratch
    mutable SelectInOrder within_;                           // scratch of within()
};

} // namespace sph
