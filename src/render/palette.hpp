#pragma once
// The frame's colours by render.background: the backdrop behind the scene
// and the overlay, the overlay's text and lines, the solids' outlines, the
// floor, and the ambient light the sky and the ground give. Light keeps
// the dark end of every colour map visible (viridis' purple, turbo's navy);
// dark is the look before light and depth came in.

#include "scene/render_choices.hpp"

#include <glm/glm.hpp>

namespace sph {

struct Palette {
    // sRGB values, as they are written to the image.
    glm::vec3 backdrop_top, backdrop_bottom; // a vertical gradient
    glm::vec4 text, bar_lines;               // the overlay's
    glm::vec4 box_lines, obstacle_fill, paddle_fill, paddle_lines;
    glm::vec3 solid; // the mesh obstacles' base colour, lit
    // Linear light: the ambient from above (sky) and below (ground).
    glm::vec3 sky, ground;
};

const Palette& palette(Background background);

} // namespace sph
