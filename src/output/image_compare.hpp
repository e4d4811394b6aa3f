#pragma once
// Compares a rendered image with a reference one, for checks in CI
// (`sphclip compare`). Only the colour counts: alpha is ignored, since
// rendered frames are opaque and a transparent pixel's colour is arbitrary.

#include "output/image.hpp"

#include <cstdint>
#include <optional>

namespace sph {

struct CompareOptions {
    double max_mean_difference = 1.0;   // mean absolute difference over RGB channels, 0-255 scale
    double pixel_threshold = 32;        // a pixel differs when any RGB channel differs by more
    double max_different_percent = 0.5; // share of differing pixels allowed, percent
    // Differing pixels allowed, as a count: a local change (a label, a
    // small square) is a tiny share of a large frame, so the share alone
    // passes it (docs: "compare's defaults").
    std::uint64_t max_different_pixels = 16;
};

// The smallest box holding every differing pixel, in pixels, inclusive.
struct PixelBox {
    int x_min = 0, y_min = 0, x_max = 0, y_max = 0;
};

struct CompareResult {
    double mean_difference = 0;   // mean |test - reference| over pixels and RGB channels, 0-255
    double max_difference = 0;    // largest |test - reference| of any channel, 0-255
    double different_percent = 0; // pixels beyond pixel_threshold, percent of all pixels
    double psnr_db = 0; // peak signal-to-noise ratio over RGB, dB; infinity when identical
    std::uint64_t different_pixels = 0;    // pixels beyond pixel_threshold
    std::optional<PixelBox> different_box; // where they are; none when there are none
    // The most differing pixels that touch one another (8-neighbours): one
    // compact change, told apart from the same count scattered.
    std::uint64_t largest_cluster = 0;
    bool match = false; // mean_difference <= max_mean_difference,
                        // different_percent <= max_different_percent and
                        // different_pixels <= max_different_pixels
};

// Throws std::invalid_argument when the sizes differ.
CompareResult compare_images(const Image& reference, const Image& test,
                             const CompareOptions& options);

// The differences made visible, the size of the inputs: the reference as
// faint grey where the pixels agree, differences up to the threshold in blue,
// pixels beyond the threshold in red, brighter the larger the difference.
// Opaque. Throws std::invalid_argument when the sizes differ.
Image difference_image(const Image& reference, const Image& test, const CompareOptions& options);

} // namespace sph
