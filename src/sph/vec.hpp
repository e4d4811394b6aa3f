#pragma once
// Vector types shared by the whole core. The dimension is a template parameter
// (2 or 3) so every stage is written once and compiled for both.

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace sph {

using Real = double;

template <int D>
using Vec = glm::vec<D, Real, glm::defaultp>;

template <int D>
concept SupportedDimension = (D == 2 || D == 3);

// Axis-aligned box [min, max].
template <int D>
struct Box {
    Vec<D> min{0};
    Vec<D> max{1};

    // Strictly inside (a point on a face is not).
    bool contains(const Vec<D>& x) const {
        for (int a = 0; a < D; ++a)
            if (!(x[a] > min[a] && x[a] < max[a]))
                return false;
        return true;
    }
};

template <int D>
inline Real squared_length(const Vec<D>& v) {
    return glm::dot(v, v);
}

} // namespace sph
