#include "sph/neighbours/spatial_hash.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace sph {

template <int D>
typename SpatialHash<D>::Cell SpatialHash<D>::cell_of(const Vec<D>& x) const {
    Cell c;
    for (int a = 0; a < D; ++a)
        c[a] = static_cast<std::int64_t>(std::floor(x[a] / cell_size_));
    return c;
}

template <int D>
std::uint32_t SpatialHash<D>::key_of(const Cell& c) const {
    constexpr std::array<std::uint64_t, 3> primes{73856093u, 19349663u, 83492791u};
    std::uint64_t hash = 0;
    for (int a = 0; a < D; ++a)
        hash ^= static_cast<std::uint64_t>(c[a]) * primes[a];
    return static_cast<std::uint32_t>(hash % table_size_);
}

template <int D>
template <class Visit>
void SpatialHash<D>::for_each_candidate(const Vec<D>& x, Visit&& visit) const {
    // Keys of the 3^D surrounding cells. Two cells can share a key; each key
    // is walked once, or its particles would be counted twice.
    constexpr int cell_count = D == 2 ? 9 : 27;
    std::array<std::uint32_t, cell_count> keys;
    const Cell centre = cell_of(x);
    for (int k = 0; k < cell_count; ++k) {
        Cell c = centre;
        int rest = k;
        for (int a = 0; a < D; ++a) {
            c[a] += rest % 3 - 1;
            rest /= 3;
        }
        keys[k] = key_of(c);
    }
    std::sort(keys.begin(), keys.end());
    const auto last = std::unique(keys.begin(), keys.end());
    for (auto key = keys.begin(); key != last; ++key) {
        for (std::uint32_t e = start_[*key]; e < lookup_.size() && lookup_[e].first == *key; ++e)
            visit(lookup_[e].second);
    }
}

template <int D>
void SpatialHash<D>::find(std::span<const Vec<D>> positions, Real radius, NeighbourList& out) {
    const std::size_t n = positions.size();
    cell_size_ = radius;
    table_size_ = static_cast<std::uint32_t>(std::max<std::size_t>(n, 1));

    // Spatial lookup sorted by key; ties by particle index keep it deterministic.
    lookup_.resize(n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        lookup_[i] = {key_of(cell_of(positions[i])), static_cast<std::uint32_t>(i)};
    std::sort(lookup_.begin(), lookup_.end());

    start_.assign(table_size_, empty_key_start);
    for (std::size_t e = n; e-- > 0;)
        start_[lookup_[e].first] = static_cast<std::uint32_t>(e);

    // Two passes (count, then fill) so each particle writes only its own row.
    const Real r2 = radius * radius;
    out.start.resize(n + 1);
    out.start[0] = 0;
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t count = 0;
        for_each_candidate(positions[i], [&](std::uint32_t j) {
            count += (j != i && squared_length<D>(positions[i] - positions[j]) < r2);
        });
        out.start[i + 1] = count;
    }
    for (std::size_t i = 0; i < n; ++i)
        out.start[i + 1] += out.start[i];
    out.size_for(out.start[n]);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t* row = out.index.data() + out.start[i];
        for_each_candidate(positions[i], [&](std::uint32_t j) {
            if (j != i && squared_length<D>(positions[i] - positions[j]) < r2)
                *row++ = j;
        });
    }
}

template class SpatialHash<2>;
template class SpatialHash<3>;

} // namespace sph
