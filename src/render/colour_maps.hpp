#pragma once
// Perceptual colour maps, as tables the renderer uploads as 1D textures.

#include "scene/render_choices.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

using Rgb8 = std::array<std::uint8_t, 3>;

// viridis (sequential), turbo (rainbow-like but perceptually ordered),
// diverging (blue - grey - red, for a quantity around a reference value).
const std::vector<std::string>& colour_map_names();

// `size` colours from the low end to the high end.
std::vector<Rgb8> colour_map_table(ColourMap map, int size = 256);
// The same for the map spelled `name`; throws std::invalid_argument for an
// unknown name.
std::vector<Rgb8> colour_map_table(std::string_view name, int size = 256);

} // namespace sph
