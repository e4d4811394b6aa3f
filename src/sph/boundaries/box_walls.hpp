#pragma once
// Walls of the domain box (solver.walls): reflecting, or particles
// (BoundaryParticles::box_walls) with the reflection kept as the last guard.

#include "sph/boundaries/boundary.hpp"

namespace sph {

// The seed's collision: a particle found outside the box is put back on the
// wall it crossed and its velocity reflected, v - 2 (v.n) n. Only a particle
// moving outwards is reflected, so a reflection never sends it back out.
template <int D>
void reflect_at_box(const Box<D>& box, State<D>& state) {
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        Vec<D>& x = state.position[i];
        Vec<D>& v = state.velocity[i];
        for (int a = 0; a < D; ++a) {
            if (x[a] < box.min[a]) {
                x[a] = box.min[a];
                if (v[a] < 0)
                    v[a] = -v[a];
            } else if (x[a] > box.max[a]) {
                x[a] = box.max[a];
                if (v[a] > 0)
                    v[a] = -v[a];
            }
        }
    }
}

// The domain's walls in the boundary list: every scene has them.
template <int D>
class BoxWalls final : public Boundary<D> {
  public:
    explicit BoxWalls(const Box<D>& domain) : domain_(domain) {}
    std::string_view name() const override { return "walls"; }
    // Reflections are not counted: they are the box's ordinary collisions.
    std::size_t keep_out(Real, State<D>& state) const override {
        reflect_at_box(domain_, state);
        return 0;
    }

  private:
    Box<D> domain_;
};

} // namespace sph
