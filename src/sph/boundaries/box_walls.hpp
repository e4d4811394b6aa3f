#pragma once
// Walls of the domain box.

#include "sph/params.hpp"
#include "sph/state.hpp"

namespace sph {

// The seed's collision: a particle found outside the box is put back on the
// wall it crossed and its velocity reflected, v - 2 (v.n) n. Only a particle
// moving outwards is reflected, so a reflection never sends it back out.
template <int D>
void reflect_at_box(const Params<D>& params, State<D>& state) {
    const std::size_t n = state.size();
    const Box<D>& box = params.domain;
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

} // namespace sph
