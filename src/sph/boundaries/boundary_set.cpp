#include "sph/boundaries/boundary_set.hpp"

#include "sph/boundaries/box_walls.hpp"

namespace sph {

template <int D>
BoundaryList<D> make_boundaries(const Params<D>& p) {
    BoundaryList<D> boundaries;
    boundaries.push_back(std::make_unique<BoxWalls<D>>(p.domain));
    if (!p.obstacles.empty())
        boundaries.push_back(std::make_unique<ObstacleSet<D>>(p.obstacles));
    if (!p.paddles.empty())
        boundaries.push_back(std::make_unique<PaddleSet<D>>(p.paddles));
    return boundaries;
}

namespace {

// The static particles: the obstacles' shells, and the domain walls' when
// they are particles. None when neither exists.
template <int D>
std::optional<BoundaryParticles<D>> static_particles(const Params<D>& p) {
    const Real lattice_volume = p.mass / p.rest_density;
    BoundarySamples<D> samples = sample_obstacles<D>(p.obstacles, p.spacing, p.h, lattice_volume);
    if (p.walls == WallModel::particles) {
        // Not const: returned, it is moved, not copied (the walls of a large
        // tank are 10-20 MB).
        auto walls = BoundaryParticles<D>::box_walls(p.domain, p.spacing, p.h, lattice_volume);
        if (samples.positions.empty())
            return walls;
        samples.positions.insert(samples.positions.end(), walls.positions().begin(),
                                 walls.positions().end());
        samples.volumes.insert(samples.volumes.end(), walls.volumes().begin(),
                               walls.volumes().end());
    } else if (samples.positions.empty()) {
        return std::nullopt;
    }
    return BoundaryParticles<D>(std::move(samples.positions), std::move(samples.volumes), p.h);
}

} // namespace

template <int D>
std::optional<BoundaryParticles<D>> make_boundary_particles(const Params<D>& p) {
    std::optional<BoundaryParticles<D>> boundary = static_particles(p);
    if (p.paddles.empty())
        return boundary;
    // The paddles' shells join the set as its moving particles, after the
    // static ones (a set of their own when there are no static ones).
    if (!boundary)
        boundary.emplace(std::vector<Vec<D>>{}, std::vector<Real>{}, p.h);
    PaddleSamples<D> samples =
        sample_paddles<D>(p.paddles, p.spacing, p.h, p.mass / p.rest_density);
    boundary->add_moving(std::move(samples.positions), std::move(samples.volumes),
                         std::move(samples.paddle));
    return boundary;
}

template BoundaryList<2> make_boundaries<2>(const Params<2>&);
template BoundaryList<3> make_boundaries<3>(const Params<3>&);
template std::optional<BoundaryParticles<2>> make_boundary_particles<2>(const Params<2>&);
template std::optional<BoundaryParticles<3>> make_boundary_particles<3>(const Params<3>&);

} // namespace sph
