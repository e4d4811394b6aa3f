// The render benchmark's drawing variants (tests/bench/render_variants.*):
// without a variant they draw the renderer's frame, pixel for pixel; with
// one, nearly the same picture.
#include "output/image_compare.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "render_variants.hpp"
#include "support/particle_lattice.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sph;
using sph::test::lattice;

namespace {

// A cube of spheres `spacing` apart in a 0.1 m domain, seen from front right.
RenderSettings cube_view(double spacing, int width, int height) {
    RenderSettings r;
    r.width = width;
    r.height = height;
    r.dimension = 3;
    r.radius = 0.5 * spacing;
    r.range = {0, 0.1};
    r.domain_min = glm::dvec3(0);
    r.domain_max = glm::dvec3(0.1);
    r.camera_target = glm::dvec3(0.05);
    r.camera_position = glm::dvec3(0.05) + 0.25 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
    return r;
}

} // namespace

TEST_CASE("without a variant, the variant renderer draws the renderer's frame", "[render]") {
    const double spacing = 0.005;
    for (const char* backend : {"egl", "osmesa"})
        for (int dimension : {2, 3})
            for (const char* spheres : {"impostor", "mesh"}) {
                INFO(backend << ", " << dimension << "D, " << spheres);
                const Snapshot snapshot = lattice(dimension, dimension == 3 ? 12 : 20, spacing);
                RenderSettings r = cube_view(spacing, 320, 180);
                r.dimension = dimension;
                r.spheres = *choice_named<SphereDrawing>(spheres);
                if (dimension == 2)
                    r.domain_max = glm::dvec3(0.1, 0.1, 0);
                auto context = make_gl_context(backend);
                FrameRenderer renderer(r);
                VariantRenderer variant(r, DrawVariant{});
                const Image image = variant.render(snapshot);
                CHECK(image.rgba == renderer.render(snapshot).rgba);
                CHECK(variant.last_drawn() == renderer.last_drawn());
                CHECK(variant.last_flat() == 0);
            }
}

TEST_CASE("small spheres as flat discs look like ray-cast ones", "[render]") {
    // 27,000 spheres about 3 px across: flat discs, as quads or points, and
    // ray-cast impostors give nearly the same picture.
    const double spacing = 0.1 / 30;
    const Snapshot snapshot = lattice(3, 30, spacing);
    RenderSettings r = cube_view(spacing, 640, 360);
    // The benchmark's flat discs are drawn unshadowed.
    r.shadows = false;
    auto context = make_gl_context("auto");
    VariantRenderer ray_cast(r, DrawVariant{});
    const Image reference = ray_cast.render(snapshot);
    CHECK(ray_cast.last_flat() == 0);
    for (bool points : {false, true}) {
        INFO((points ? "points" : "quads"));
        VariantRenderer renderer(r, {.flat_below_px = 8, .flat_as_points = points});
        const Image image = renderer.render(snapshot);
        CHECK(renderer.last_flat() > renderer.last_drawn() / 2);
        // Mean absolute difference over the RGB channels, 0-255 (the cube
        // fills about 45% of the image).
        double sum = 0;
        for (std::size_t k = 0; k < image.rgba.size(); ++k)
            if (k % 4 != 3)
                sum += std::abs(int(image.rgba[k]) - int(reference.rgba[k]));
        CHECK(sum / double(image.rgba.size() / 4 * 3) < 3.5);
    }
}

TEST_CASE("sorted and conservative-depth spheres look like the renderer's", "[render]") {
    // Only the order of the draw and where the outline lies change, not the
    // spheres' depths: the same picture up to round-off at their edges.
    const double spacing = 0.005;
    const Snapshot snapshot = lattice(3, 16, spacing);
    const RenderSettings r = cube_view(spacing, 320, 180);
    for (const char* backend : {"egl", "osmesa"}) {
        auto context = make_gl_context(backend);
        FrameRenderer renderer(r);
        const Image reference = renderer.render(snapshot);
        for (const DrawVariant& v :
             {DrawVariant{.sort_front_to_back = true}, DrawVariant{.conservative_depth = true}}) {
            INFO(backend << (v.sort_front_to_back ? ", sorted" : ", conservative depth"));
            VariantRenderer variant(r, v);
            const CompareResult c = compare_images(reference, variant.render(snapshot), {});
            INFO("mean difference " << c.mean_difference << ", different " << c.different_percent
                                    << "%");
            CHECK(c.match);
            CHECK(variant.last_drawn() == renderer.last_drawn());
        }
    }
}
