#pragma once
// Arrays sized by the flow (pairs, wall contacts, grid cells) change size a
// little from step to step. Growing them exactly would allocate at each new
// high; a quarter of headroom makes that rare, so a step allocates nothing
// once sizes settle.

#include <cstddef>
#include <vector>

namespace sph {

template <class T>
void resize_with_headroom(std::vector<T>& array, std::size_t size) {
    if (array.capacity() < size)
        array.reserve(size + size / 4);
    array.resize(size);
}

} // namespace sph
