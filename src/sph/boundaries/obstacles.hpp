#pragma once
// Static obstacles the fluid flows around (the scene's effects.obstacles):
// boxes, spheres (circles in 2D) and, in 3D, closed triangle meshes
// (triangle_mesh.hpp), made of boundary particles, after Akinci
// et al. 2012, "Versatile rigid-fluid coupling for incompressible SPH". Each
// obstacle's solid is sampled on the fluid's spacing in a shell as deep as
// the kernel reaches, ceil(h / spacing) layers inside its surface, as the
// domain walls are outside theirs; deeper inside no fluid particle can see
// it. The samples join the domain walls' particles in the one
// BoundaryParticles set the solvers already use for density and pressure.

#include "sph/boundaries/boundary.hpp"
#include "sph/boundaries/triangle_mesh.hpp"
#include "sph/state.hpp"
#include "sph/vec.hpp"

#include <cstddef>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace sph {

enum class ObstacleShape { box, sphere, mesh };

template <int D>
struct Obstacle {
    ObstacleShape shape = ObstacleShape::box;
    Box<D> box;       // m, the box's corners
    Vec<D> centre{0}; // m, the sphere's
    Real radius = 0;  // m, the sphere's
    // The mesh's solid, in scene coordinates (3D only); shared, it is never
    // changed once built.
    std::shared_ptr<const TriangleMesh> mesh;

    // Distance to the surface, negative inside.
    Real signed_distance(const Vec<D>& x) const;
    // signed_distance(x) < d, without searching a mesh when x is at least d
    // outside its bounding box.
    bool nearer_than(const Vec<D>& x, Real d) const;
};

// Boundary particles and the volume each stands for (m^3, m^2 in 2D).
template <int D>
struct BoundarySamples {
    std::vector<Vec<D>> positions;
    std::vector<Real> volumes;
};

// The shells of every obstacle, sampled at `spacing` for a kernel of support
// h. `lattice_volume` is the volume a fluid particle has on its lattice
// (mass / rho0); a sample gets the volume of the solid it stands for, scaled
// by lattice_volume / spacing^D, so that a flat face sampled like the fluid's
// lattice gives a fluid particle beside it exactly the rest density, as the
// domain walls do. A sample inside another obstacle is left out: it would
// count that solid twice.
template <int D>
BoundarySamples<D> sample_obstacles(std::span<const Obstacle<D>> obstacles, Real spacing, Real h,
                                    Real lattice_volume);

// Whether a fluid particle placed at x at the start would sit too close to
// an obstacle: inside it, or nearer to its surface than half a spacing,
// that is nearer than one spacing to its outer layer of samples.
template <int D>
bool blocked_by_obstacle(std::span<const Obstacle<D>> obstacles, const Vec<D>& x, Real spacing);

// The last guard after each move, as the reflecting box is for the domain:
// a particle found inside an obstacle is put back on its surface, and its
// velocity into the solid reflected, v - 2 (v.n) n. The boundary particles
// alone let a thin film sink in: with few fluid neighbours a particle only
// reaches the rest density close to them. Returns how many were put back.
template <int D>
std::size_t push_out_of_obstacles(std::span<const Obstacle<D>> obstacles, State<D>& state);

// The scene's obstacles in the boundary list (present when it has any).
template <int D>
class ObstacleSet final : public Boundary<D> {
  public:
    explicit ObstacleSet(std::vector<Obstacle<D>> obstacles) : obstacles_(std::move(obstacles)) {}
    std::string_view name() const override { return "obstacles"; }
    std::size_t keep_out(Real, State<D>& state) const override {
        return push_out_of_obstacles<D>(obstacles_, state);
    }

  private:
    std::vector<Obstacle<D>> obstacles_;
};

} // namespace sph
