#include "output/image_compare.hpp"

#include "sph/assert.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sph {

namespace {

void require_same_size(const Image& reference, const Image& test) {
    SPHCLIP_ASSERT(reference.rgba.size() == std::size_t(reference.width) * reference.height * 4);
    SPHCLIP_ASSERT(test.rgba.size() == std::size_t(test.width) * test.height * 4);
    if (reference.width != test.width || reference.height != test.height)
        throw std::invalid_argument("the images differ in size: reference " +
                                    std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height) + ", test " +
                                    std::to_string(test.width) + "x" + std::to_string(test.height));
}

// Largest |test - reference| over the RGB channels of the pixel at byte i.
int channel_difference(const Image& reference, const Image& test, std::size_t i) {
    int largest = 0;
    for (std::size_t c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(int(test.rgba[i + c]) - int(reference.rgba[i + c])));
    return largest;
}

// The size of the largest group of 8-connected pixels among `pixels`
// (indices in row order, ascending), by union-find over the neighbours
// already seen: left, and the three above.
std::uint64_t largest_cluster(const std::vector<std::uint32_t>& pixels, int width) {
    std::vector<std::uint32_t> parent(pixels.size());
    std::vector<std::uint64_t> size(pixels.size(), 1);
    for (std::size_t k = 0; k < parent.size(); ++k)
        parent[k] = std::uint32_t(k);
    const auto root = [&](std::uint32_t k) {
        while (parent[k] != k)
            k = parent[k] = parent[parent[k]];
        return k;
    };
    const auto join = [&](std::uint32_t a, std::uint32_t b) {
        a = root(a);
        b = root(b);
        if (a == b)
            return;
        if (size[a] < size[b])
            std::swap(a, b);
        parent[b] = a;
        size[a] += size[b];
    };
    const auto index_of = [&](std::int64_t pixel) -> std::optional<std::uint32_t> {
        const auto it = std::lower_bound(pixels.begin(), pixels.end(), pixel,
                                         [](std::uint32_t p, std::int64_t v) { return p < v; });
        if (it == pixels.end() || std::int64_t(*it) != pixel)
            return std::nullopt;
        return std::uint32_t(it - pixels.begin());
    };
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        const std::int64_t p = pixels[k];
        const std::int64_t x = p % width;
        for (const std::int64_t dx : {-1, 0, 1}) {
            if (x + dx < 0 || x + dx >= width)
                continue;
            if (const auto above = index_of(p - width + dx))
                join(std::uint32_t(k), *above);
        }
        if (x > 0)
            if (const auto left = index_of(p - 1))
                join(std::uint32_t(k), *left);
    }
    std::uint64_t largest = 0;
    for (std::size_t k = 0; k < pixels.size(); ++k)
        if (parent[k] == k)
            largest = std::max(largest, size[k]);
    return largest;
}

} // namespace

CompareResult compare_images(const Image& reference, const Image& test,
                             const CompareOptions& options) {
    require_same_size(reference, test);
    // Integer sums are exact: 255^2 x 3 channels x 2^31 pixels fits in 64 bits.
    std::uint64_t sum = 0, sum_of_squares = 0, different = 0;
    int largest = 0;
    std::vector<std::uint32_t> differing; // pixel indices, in row order
    for (std::size_t i = 0; i < reference.rgba.size(); i += 4) {
        int pixel_largest = 0;
        for (std::size_t c = 0; c < 3; ++c) {
            const int d = std::abs(int(test.rgba[i + c]) - int(reference.rgba[i + c]));
            sum += std::uint64_t(d);
            sum_of_squares += std::uint64_t(d * d);
            pixel_largest = std::max(pixel_largest, d);
        }
        if (pixel_largest > options.pixel_threshold) {
            ++different;
            differing.push_back(std::uint32_t(i / 4));
        }
        largest = std::max(largest, pixel_largest);
    }

    CompareResult result;
    result.different_pixels = different;
    if (!differing.empty()) {
        PixelBox box{reference.width, reference.height, -1, -1};
        for (const std::uint32_t p : differing) {
            const int x = int(p % std::uint32_t(reference.width));
            const int y = int(p / std::uint32_t(reference.width));
            box = {std::min(box.x_min, x), std::min(box.y_min, y), std::max(box.x_max, x),
                   std::max(box.y_max, y)};
        }
        result.different_box = box;
        result.largest_cluster = largest_cluster(differing, reference.width);
    }
    const std::size_t pixels = reference.rgba.size() / 4;
    if (pixels > 0) {
        const double samples = 3.0 * double(pixels);
        result.mean_difference = double(sum) / samples;
        result.different_percent = 100.0 * double(different) / double(pixels);
        result.psnr_db =
            sum_of_squares == 0
                ? std::numeric_limits<double>::infinity()
                : 10.0 * std::log10(255.0 * 255.0 / (double(sum_of_squares) / samples));
    } else {
        result.psnr_db = std::numeric_limits<double>::infinity();
    }
    result.max_difference = largest;
    result.match = result.mean_difference <= options.max_mean_difference &&
                   result.different_percent <= options.max_different_percent &&
                   result.different_pixels <= options.max_different_pixels;
    return result;
}

Image difference_image(const Image& reference, const Image& test, const CompareOptions& options) {
    require_same_size(reference, test);
    const double threshold = options.pixel_threshold;
    Image diff(reference.width, reference.height);
    for (std::size_t i = 0; i < reference.rgba.size(); i += 4) {
        const std::uint8_t* ref = &reference.rgba[i];
        std::uint8_t* out = &diff.rgba[i];
        const int d = channel_difference(reference, test, i);
        // Dark enough that blue and red stand out, light enough to recognise the picture.
        const int luma = (77 * ref[0] + 150 * ref[1] + 29 * ref[2]) >> 8;
        const auto grey = std::uint8_t(24 + luma / 4);
        if (d > threshold) {
            const double t = (d - threshold) / std::max(255.0 - threshold, 1.0);
            out[0] = std::uint8_t(std::lround(160 + 95 * std::clamp(t, 0.0, 1.0)));
            out[1] = 0;
            out[2] = 0;
        } else if (d > 0) {
            const double t = double(d) / std::max(threshold, 1.0);
            out[0] = grey / 2;
            out[1] = grey / 2;
            out[2] = std::uint8_t(std::lround(96 + 159 * std::clamp(t, 0.0, 1.0)));
        } else {
            out[0] = out[1] = out[2] = grey;
        }
        out[3] = 255;
    }
    return diff;
}

} // namespace sph
