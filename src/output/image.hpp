#pragma once
// An 8-bit RGBA image, rows from the top of the picture down. What the
// renderer reads back from GL and what the PNG and MP4 writers and `compare`
// take.

#include <cstdint>
#include <vector>

namespace sph {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // width * height * 4, row 0 is the top row

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * std::size_t(h) * 4, 0) {}
    std::uint8_t* pixel(int x, int y) { return rgba.data() + (std::size_t(y) * width + x) * 4; }
    const std::uint8_t* pixel(int x, int y) const {
        return rgba.data() + (std::size_t(y) * width + x) * 4;
    }
};

} // namespace sph
