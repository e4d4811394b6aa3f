#pragma once
// Vector types shared by the whole core. The dimension is a template parameter
// (2 or 3) so every stage is written once and compiled for both.

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>

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

    // Puts x, a point inside, on the face nearest to it, exactly (not by
    // arithmetic that could round back inside), and returns that face's
    // outward normal. The last guards of obstacles and paddles use it.
    Vec<D> put_on_nearest_face(Vec<D>& x) const {
        int axis = 0, side = 1;
        Real nearest = std::numeric_limits<Real>::infinity();
        for (int a = 0; a < D; ++a) {
            if (x[a] - min[a] < nearest) {
                nearest = x[a] - min[a];
                axis = a;
                side = -1;
            }
            if (max[a] - x[a] < nearest) {
                nearest = max[a] - x[a];
                axis = a;
                side = 1;
            }
        }
        x[axis] = side > 0 ? max[axis] : min[axis];
        Vec<D> normal(0);
        normal[axis] = Real(side);
        return normal;
    }
};

template <int D>
inline Real squared_length(const Vec<D>& v) {
    return glm::dot(v, v);
}

} // namespace sph
