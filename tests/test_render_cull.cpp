// Culling particles outside the view (RenderSettings::cull_outside_view):
// a sphere that lies wholly outside the view colours no pixel, so the frame
// with culling is pixel for pixel the frame without it, with either backend
// and sphere technique, in 3D (perspective) and 2D (orthographic).
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "support/particle_lattice.hpp"

#include <catch2/catch.hpp>

using namespace sph;
using sph::test::lattice;

namespace {

RenderSettings settings_for(int dimension, const std::string& spheres, double spacing) {
    RenderSettings r;
    r.width = 320;
    r.height = 180;
    r.dimension = dimension;
    r.spheres = *choice_named<SphereDrawing>(spheres);
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
            // With shadows nothing is culled: a particle outside the view
            // may shadow one inside it.
            r.shadows = true;
            const Frames shadowed = render_both(r, snapshot, backend);
            CHECK(shadowed.outside == 0);
            CHECK(shadowed.culled.rgba == shadowed.all.rgba);
            r.shadows = false;
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
