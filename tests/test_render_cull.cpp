// Culling particles outside the view (RenderSettings::cull_outside_view):
// a sphere that lies wholly outside the view colours no pixel, so the frame
// with culling is pixel for pixel the frame without it, with either backend
// and sphere technique, in 3D (perspective) and 2D (orthographic).
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace sph;

namespace {

// A lattice of side^3 (3D) or side^2 (2D) particles `spacing` apart from the
// origin, speeds varying with height so the colour map shows.
Snapshot lattice(int dimension, int side, double spacing) {
    Snapshot s;
    s.dimension = dimension;
    const int nz = dimension == 3 ? side : 1;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) {
                const double x = (i + 0.5) * spacing, y = (j + 0.5) * spacing;
                s.position.insert(s.position.end(), {x, y});
                s.velocity.insert(s.velocity.end(), {y, 0});
                if (dimension == 3) {
                    s.position.push_back((k + 0.5) * spacing);
                    s.velocity.push_back(0);
                }
                s.density.push_back(1000);
                s.pressure.push_back(0);
                s.id.push_back(std::uint32_t(s.id.size()));
            }
    return s;
}

RenderSettings settings_for(int dimension, const std::string& spheres, double spacing) {
    RenderSettings r;
    r.width = 320;
    r.height = 180;
    r.dimension = dimension;
    r.spheres = spheres;
    r.radius = 0.5 * spacing;
    r.range = {0, 0.1};
    return r;
}

struct Frames {
    Image culled, all;
    std::size_t outside = 0, drawn_culled = 0, drawn_all = 0;
};

Frames render_both(const RenderSettings& settings, const Snapshot& snapshot,
                   std::string_view backend) {
    auto context = make_gl_context(backend);
    Frames f;
    RenderSettings with = settings, without = settings;
    with.cull_outside_view = true;
    without.cull_outside_view = false;
    FrameRenderer culling(with), drawing_all(without);
    f.culled = culling.render(snapshot);
    f.outside = culling.last_outside_view();
    f.drawn_culled = culling.last_drawn();
    f.all = drawing_all.render(snapshot);
    f.drawn_all = drawing_all.last_drawn();
    CHECK(drawing_all.last_outside_view() == 0);
    return f;
}

} // namespace

TEST_CASE("culling particles outside the view leaves the 3D frame unchanged", "[render]") {
    // A 0.1 m cube of 8,000 particles seen from close by, looking past its
    // corner: most of it is outside the view, some of it straddles the edges.
    const double spacing = 0.005;
    const Snapshot snapshot = lattice(3, 20, spacing);
    for (const char* backend : {"egl", "osmesa"})
        for (const char* spheres : {"impostor", "mesh"}) {
            INFO(backend << ", " << spheres);
            RenderSettings r = settings_for(3, spheres, spacing);
            r.domain_min = glm::dvec3(0);
            r.domain_max = glm::dvec3(0.1);
            r.camera_position = {0.13, 0.12, 0.14};
            r.camera_target = {0.08, 0.07, 0.06};
            r.fov = 30;
            const Frames f = render_both(r, snapshot, backend);
            CHECK(f.outside > 0);
            CHECK(f.drawn_culled + f.outside == f.drawn_all);
            CHECK(f.drawn_culled > 0);
            CHECK(f.culled.rgba == f.all.rgba);
        }
}

TEST_CASE("culling particles outside the view leaves the 2D frame unchanged", "[render]") {
    // Particles thrown far out of a small domain, as a splash leaves it: the
    // camera fits the domain, so many are outside the view.
    const double spacing = 0.004;
    Snapshot snapshot = lattice(2, 60, spacing); // 0.24 m square
    for (std::size_t i = 0; i < snapshot.size(); ++i)
        snapshot.position[2 * i] -= 0.08;
    RenderSettings r = settings_for(2, "impostor", spacing);
    r.domain_min = glm::dvec3(0, 0, 0);
    r.domain_max = glm::dvec3(0.1, 0.06, 0);
    for (const char* backend : {"egl", "osmesa"}) {
        INFO(backend);
        const Frames f = render_both(r, snapshot, backend);
        CHECK(f.outside > 0);
        CHECK(f.drawn_culled + f.outside == f.drawn_all);
        CHECK(f.culled.rgba == f.all.rgba);
    }
}

TEST_CASE("small spheres as flat discs look like ray-cast ones", "[render]") {
    // 27,000 spheres about 3 px across: flat discs, as quads or points, and
    // ray-cast impostors give nearly the same picture.
    const double spacing = 0.1 / 30;
    const Snapshot snapshot = lattice(3, 30, spacing);
    RenderSettings r = settings_for(3, "impostor", spacing);
    r.width = 640;
    r.height = 360;
    r.domain_min = glm::dvec3(0);
    r.domain_max = glm::dvec3(0.1);
    r.camera_target = glm::dvec3(0.05);
    r.camera_position = glm::dvec3(0.05) + 0.25 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
    auto context = make_gl_context("auto");
    FrameRenderer ray_cast(r);
    const Image reference = ray_cast.render(snapshot);
    CHECK(ray_cast.last_flat() == 0);
    for (bool points : {false, true}) {
        INFO((points ? "points" : "quads"));
        RenderSettings flat = r;
        flat.flat_below_px = 8;
        flat.flat_as_points = points;
        FrameRenderer renderer(flat);
        const Image image = renderer.render(snapshot);
        CHECK(renderer.last_flat() > renderer.last_drawn() / 2);
        // Mean absolute difference over the RGB channels, 0-255.
        double sum = 0;
        for (std::size_t k = 0; k < image.rgba.size(); ++k)
            if (k % 4 != 3)
                sum += std::abs(int(image.rgba[k]) - int(reference.rgba[k]));
        CHECK(sum / double(image.rgba.size() / 4 * 3) < 3.0);
    }
}
