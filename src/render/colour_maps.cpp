#include "render/colour_maps.hpp"

#include <cmath>
#include <stdexcept>

namespace sph {

namespace {

// Each map is given by evenly spaced key colours (sRGB hex) read off the
// published maps and interpolated linearly between them: viridis (van der
// Walt & Smith, matplotlib 2015), turbo (Mikhailov, Google 2019), and
// Moreland's cool-warm diverging map (2009).
constexpr std::uint32_t viridis[] = {0x440154, 0x482878, 0x3e4989, 0x31688e, 0x26828e,
                                     0x1f9e89, 0x35b779, 0x6ece58, 0xb5de2b, 0xfde725};
constexpr std::uint32_t turbo[] = {0x30123b, 0x4145ab, 0x4675ed, 0x39a2fc, 0x1bcfd4,
                                   0x24eca6, 0x61fc6c, 0xa4fc3b, 0xd1e835, 0xf3c63a,
                                   0xfe9b2d, 0xf36315, 0xd93806, 0xb11901, 0x7a0402};
constexpr std::uint32_t diverging[] = {0x3b4cc0, 0x6282ea, 0x8db0fe, 0xb8d0f9, 0xdddcdc,
                                       0xf5c4ad, 0xf49a7b, 0xde604d, 0xb40426};

template <std::size_t N>
std::vector<Rgb8> interpolate(const std::uint32_t (&keys)[N], int size) {
    std::vector<Rgb8> table(size);
    for (int i = 0; i < size; ++i) {
        const double position = size > 1 ? double(i) / (size - 1) * (N - 1) : 0;
        const std::size_t k = std::min<std::size_t>(std::size_t(position), N - 2);
        const double f = position - double(k);
        for (int c = 0; c < 3; ++c) {
            const double a = double((keys[k] >> (16 - 8 * c)) & 0xff);
            const double b = double((keys[k + 1] >> (16 - 8 * c)) & 0xff);
            table[i][c] = static_cast<std::uint8_t>(std::lround(a + f * (b - a)));
        }
    }
    return table;
}

} // namespace

const std::vector<std::string>& colour_map_names() {
    return choice_names<ColourMap>();
}

std::vector<Rgb8> colour_map_table(ColourMap map, int size) {
    switch (map) {
    case ColourMap::viridis:
        return interpolate(viridis, size);
    case ColourMap::turbo:
        return interpolate(turbo, size);
    case ColourMap::diverging:
        break;
    }
    return interpolate(diverging, size);
}

std::vector<Rgb8> colour_map_table(std::string_view name, int size) {
    if (const auto map = choice_named<ColourMap>(name))
        return colour_map_table(*map, size);
    throw std::invalid_argument("unknown colour map: " + std::string(name));
}

} // namespace sph
