#include "sph/boundaries/boundary_set.hpp"

#include "sph/boundaries/box_walls.hpp"

#include <limits>

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

template <int D>
BoundarySamples<D> obstacle_shells(const Params<D>& p) {
    return sample_obstacles<D>(p.obstacles, p.spacing, p.h, p.mass / p.rest_density);
}

// The obstacles' shells and the domain walls' particles; with a region,
// those in it only, on the whole set's grid.
template <int D>
std::optional<BoundaryParticles<D>>
make_static_boundary_particles(const Params<D>& p, const Box<D>* region,
                               const BoundarySamples<D>* shells) {
    const Real lattice_volume = p.mass / p.rest_density;
    BoundarySamples<D> samples;
    if (!shells) {
        samples = obstacle_shells(p);
        shells = &samples;
    }
    if (p.walls != WallModel::particles && shells->positions.empty())
        return std::nullopt;
    Box<D> whole{Vec<D>(std::numeric_limits<Real>::max()),
                 Vec<D>(std::numeric_limits<Real>::lowest())};
    for (const Vec<D>& x : shells->positions) {
        whole.min = glm::min(whole.min, x);
        whole.max = glm::max(whole.max, x);
    }
    std::vector<Vec<D>> walls;
    if (p.walls == WallModel::particles) {
        Box<D> bounds;
        walls = BoundaryParticles<D>::box_wall_sites(p.domain, p.spacing, p.h, region, bounds);
        whole.min = glm::min(whole.min, bounds.min);
        whole.max = glm::max(whole.max, bounds.max);
    }
    if (region) {
        BoundarySamples<D> kept;
        for (std::size_t b = 0; b < shells->positions.size(); ++b) {
            const Vec<D>& x = shells->positions[b];
            if (glm::all(glm::greaterThanEqual(x, region->min)) &&
                glm::all(glm::lessThanEqual(x, region->max))) {
                kept.positions.push_back(x);
                kept.volumes.push_back(shells->volumes[b]);
            }
        }
        samples = std::move(kept);
    } else if (shells != &samples) {
        samples = *shells;
    }
    // (Not const: returned, it is moved, not copied; the walls of a large
    // tank are 10-20 MB.)
    if (samples.positions.empty() && !region) {
        auto only_walls = BoundaryParticles<D>(std::move(walls), p.h, lattice_volume);
        return only_walls;
    }
    samples.positions.insert(samples.positions.end(), walls.begin(), walls.end());
    samples.volumes.resize(samples.positions.size(), lattice_volume);
    if (region)
        return BoundaryParticles<D>(std::move(samples.positions), std::move(samples.volumes), p.h,
                                    whole);
    return BoundaryParticles<D>(std::move(samples.positions), std::move(samples.volumes), p.h);
}

template <int D>
std::optional<BoundaryParticles<D>> make_boundary_particles(const Params<D>& p,
                                                            const Box<D>* region) {
    std::optional<BoundaryParticles<D>> boundary = make_static_boundary_particles(p, region);
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
template BoundarySamples<2> obstacle_shells<2>(const Params<2>&);
template BoundarySamples<3> obstacle_shells<3>(const Params<3>&);
template std::optional<BoundaryParticles<2>>
make_static_boundary_particles<2>(const Params<2>&, const Box<2>*, const BoundarySamples<2>*);
template std::optional<BoundaryParticles<3>>
make_static_boundary_particles<3>(const Params<3>&, const Box<3>*, const BoundarySamples<3>*);
template std::optional<BoundaryParticles<2>> make_boundary_particles<2>(const Params<2>&,
                                                                        const Box<2>*);
template std::optional<BoundaryParticles<3>> make_boundary_particles<3>(const Params<3>&,
                                                                        const Box<3>*);

} // namespace sph
