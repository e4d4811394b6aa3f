#include "render/palette.hpp"

namespace sph {

const Palette& palette(Background background) {
    // A pale, slightly cool studio grey, darker towards the floor: every
    // map's darkest colour has at least 4:1 contrast against it (viridis'
    // #440154 against #c9ced6), and the light top keeps the map's bright end
    // apart from it by its hue.
    static const Palette light{
        .backdrop_top = {0.88f, 0.89f, 0.91f},
        .backdrop_bottom = {0.78f, 0.80f, 0.83f},
        .text = {0.10f, 0.11f, 0.13f, 1.f},
        .bar_lines = {0.25f, 0.27f, 0.30f, 1.f},
        .box_lines = {0.36f, 0.39f, 0.44f, 1.f},
        .obstacle_fill = {0.56f, 0.58f, 0.62f, 1.f},
        .paddle_fill = {0.66f, 0.56f, 0.44f, 1.f},
        .paddle_lines = {0.42f, 0.32f, 0.20f, 1.f},
        .solid = {0.62f, 0.60f, 0.56f},
        .sky = {0.34f, 0.35f, 0.37f},
        .ground = {0.10f, 0.10f, 0.10f},
    };
    static const Palette dark{
        .backdrop_top = {0.08f, 0.09f, 0.11f},
        .backdrop_bottom = {0.08f, 0.09f, 0.11f},
        .text = {0.90f, 0.91f, 0.93f, 1.f},
        .bar_lines = {0.85f, 0.86f, 0.88f, 1.f},
        .box_lines = {0.55f, 0.58f, 0.62f, 1.f},
        .obstacle_fill = {0.30f, 0.32f, 0.36f, 1.f},
        .paddle_fill = {0.45f, 0.38f, 0.30f, 1.f},
        .paddle_lines = {0.78f, 0.66f, 0.50f, 1.f},
        .solid = {0.62f, 0.60f, 0.56f},
        .sky = {0.22f, 0.22f, 0.23f},
        .ground = {0.06f, 0.06f, 0.06f},
    };
    return background == Background::dark ? dark : light;
}

} // namespace sph
