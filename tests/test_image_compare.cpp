// Image comparison (src/output/image_compare.*): the metrics on cases whose
// values are known by hand, the verdict on either side of each threshold, and
// the difference image.

#include "output/image_compare.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace {

// A smooth opaque gradient that stays clear of 0 and 255, so that noise added
// to it is never clipped.
sph::Image gradient(int width, int height) {
    sph::Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = std::uint8_t(20 + 200 * x / width);
            p[1] = std::uint8_t(20 + 200 * y / height);
            p[2] = std::uint8_t(120);
            p[3] = 255;
        }
    return image;
}

// `image` with every RGB channel moved by at most 2: the cycle's magnitudes
// sum to 8 over 10 values, so the mean absolute difference is exactly 0.8 on
// any image whose channel count is a multiple of 10.
sph::Image with_noise(sph::Image image) {
    constexpr int cycle[10] = {0, 1, -1, 2, -2, 0, 1, -1, 0, 0};
    std::size_t k = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c)
            image.rgba[i + c] = std::uint8_t(image.rgba[i + c] + cycle[k++ % 10]);
    return image;
}

const sph::CompareOptions defaults;

} // namespace

TEST_CASE("identical images match, with no difference and infinite PSNR", "[compare]") {
    const sph::Image image = gradient(64, 48);
    const auto result = sph::compare_images(image, image, defaults);
    CHECK(result.match);
    CHECK(result.mean_difference == 0);
    CHECK(result.max_difference == 0);
    CHECK(result.different_percent == 0);
    CHECK(std::isinf(result.psnr_db));
    CHECK(result.psnr_db > 0);
}

TEST_CASE("the metrics of simple differences are the hand-computed values", "[compare]") {
    SECTION("one channel of one pixel off by 255") {
        sph::Image reference(1, 1), test(1, 1);
        test.rgba[0] = 255;
        const auto result = sph::compare_images(reference, test, defaults);
        CHECK(result.mean_difference == Approx(255.0 / 3));
        CHECK(result.max_difference == 255);
        CHECK(result.different_percent == 100);
        // MSE = 255^2 / 3, so PSNR = 10 log10(3).
        CHECK(result.psnr_db == Approx(10 * std::log10(3.0)));
        CHECK_FALSE(result.match);
    }
    SECTION("every channel off by one") {
        const sph::Image reference = gradient(10, 10);
        sph::Image test = reference;
        for (std::size_t i = 0; i < test.rgba.size(); i += 4)
            for (std::size_t c = 0; c < 3; ++c)
                test.rgba[i + c] += 1;
        const auto result = sph::compare_images(reference, test, defaults);
        CHECK(result.mean_difference == Approx(1));
        CHECK(result.max_difference == 1);
        CHECK(result.different_percent == 0);
        CHECK(result.psnr_db == Approx(20 * std::log10(255.0))); // MSE = 1
        CHECK(result.match);                                     // the tolerance is inclusive
    }
}

TEST_CASE("one pixel changed strongly: the verdict follows the pixel thresholds", "[compare]") {
    // 1 pixel of 100 is 1 %, above the default 0.5 %; its mean difference,
    // 60 / 300 = 0.2, is within the default tolerance.
    const sph::Image reference = gradient(10, 10);
    sph::Image test = reference;
    test.pixel(3, 7)[0] += 60;
    const auto result = sph::compare_images(reference, test, defaults);
    CHECK(result.different_percent == Approx(1));
    CHECK(result.mean_difference == Approx(0.2));
    CHECK(result.max_difference == 60);
    CHECK_FALSE(result.match);

    sph::CompareOptions options;
    options.max_different_percent = 2;
    CHECK(sph::compare_images(reference, test, options).match);

    // A pixel differs only when a channel differs by more than the threshold.
    options = defaults;
    options.pixel_threshold = 60;
    CHECK(sph::compare_images(reference, test, options).different_percent == 0);
    CHECK(sph::compare_images(reference, test, options).match);
    options.pixel_threshold = 59;
    CHECK(sph::compare_images(reference, test, options).different_percent == Approx(1));
    CHECK_FALSE(sph::compare_images(reference, test, options).match);
}

TEST_CASE("small noise everywhere matches by default, not with a tight tolerance", "[compare]") {
    const sph::Image reference = gradient(40, 30);
    const sph::Image test = with_noise(reference);
    const auto result = sph::compare_images(reference, test, defaults);
    CHECK(result.mean_difference == Approx(0.8));
    CHECK(result.max_difference == 2);
    CHECK(result.different_percent == 0);
    CHECK(std::isfinite(result.psnr_db));
    CHECK(result.match);

    sph::CompareOptions tight;
    tight.max_mean_difference = 0.5;
    CHECK_FALSE(sph::compare_images(reference, test, tight).match);

    // A threshold of 1 counts the pixels with a channel off by 2: 4 in 10.
    sph::CompareOptions strict_pixels;
    strict_pixels.pixel_threshold = 1;
    CHECK(sph::compare_images(reference, test, strict_pixels).different_percent == Approx(40));
    CHECK_FALSE(sph::compare_images(reference, test, strict_pixels).match);
}

TEST_CASE("a shifted image fails on both the mean and the share of pixels", "[compare]") {
    // An edge moved by one column: what a renderer regression looks like.
    sph::Image reference(32, 32), test(32, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            reference.pixel(x, y)[0] = x < 16 ? 0 : 200;
            test.pixel(x, y)[0] = x < 17 ? 0 : 200;
        }
    const auto result = sph::compare_images(reference, test, defaults);
    CHECK(result.different_percent == Approx(100.0 / 32));
    CHECK(result.mean_difference == Approx(200.0 / 3 / 32));
    CHECK_FALSE(result.match);
}

TEST_CASE("alpha does not count", "[compare]") {
    const sph::Image reference = gradient(8, 8);
    sph::Image test = reference;
    for (std::size_t i = 3; i < test.rgba.size(); i += 4)
        test.rgba[i] = 0;
    const auto result = sph::compare_images(reference, test, defaults);
    CHECK(result.mean_difference == 0);
    CHECK(result.match);
}

TEST_CASE("images of different sizes are refused", "[compare]") {
    const sph::Image a = gradient(10, 10), b = gradient(10, 11), c = gradient(11, 10);
    CHECK_THROWS_AS(sph::compare_images(a, b, defaults), std::invalid_argument);
    CHECK_THROWS_AS(sph::compare_images(a, c, defaults), std::invalid_argument);
    CHECK_THROWS_WITH(sph::difference_image(a, b, defaults), Catch::Contains("10x11"));
}

TEST_CASE("the difference image shows where the images differ", "[compare]") {
    const sph::Image reference = gradient(20, 10);
    sph::Image test = reference;
    test.pixel(5, 2)[1] += 100; // beyond the threshold
    test.pixel(9, 9)[2] += 10;  // within it
    const sph::Image diff = sph::difference_image(reference, test, defaults);
    REQUIRE(diff.width == 20);
    REQUIRE(diff.height == 10);

    const std::uint8_t* red = diff.pixel(5, 2);
    CHECK(red[0] >= 160);
    CHECK(red[1] == 0);
    CHECK(red[2] == 0);
    const std::uint8_t* blue = diff.pixel(9, 9);
    CHECK(blue[2] >= 96);
    CHECK(blue[2] > 2 * blue[0]);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 20; ++x) {
            const std::uint8_t* p = diff.pixel(x, y);
            CHECK(p[3] == 255);
            if ((x == 5 && y == 2) || (x == 9 && y == 9))
                continue;
            // Where they agree: faint grey, darker than either mark.
            CHECK(p[0] == p[1]);
            CHECK(p[1] == p[2]);
            CHECK(p[0] < 96);
        }
    // The picture shows through: a brighter reference gives a lighter grey.
    CHECK(diff.pixel(19, 0)[0] > diff.pixel(0, 0)[0]);

    // A larger difference is a brighter red.
    sph::Image larger = reference;
    larger.pixel(5, 2)[1] += 130;
    CHECK(sph::difference_image(reference, larger, defaults).pixel(5, 2)[0] > red[0]);
}

TEST_CASE("the difference image of identical images has no marks", "[compare]") {
    const sph::Image image = gradient(16, 16);
    const sph::Image diff = sph::difference_image(image, image, defaults);
    for (std::size_t i = 0; i < diff.rgba.size(); i += 4) {
        CHECK(diff.rgba[i] == diff.rgba[i + 1]);
        CHECK(diff.rgba[i + 1] == diff.rgba[i + 2]);
    }
}
