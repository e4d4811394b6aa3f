// Camera and layout (src/render/camera.*), without a GL context: the layout
// centres the scene and the overlay's bands as one group, the 2D camera fits
// the domain into the scene's rectangle, the 3D camera centres its target
// there, and the view planes measure distances inside the view.
#include "render/camera.hpp"

#include <catch2/catch.hpp>

using namespace sph;

namespace {

// A point's place in the image, px from the top left.
glm::dvec2 pixel(const Camera& camera, const FrameLayout& layout, const glm::dvec3& point) {
    const glm::dvec4 clip = camera.clip_from_world() * glm::dvec4(point - camera.origin, 1.0);
    return {(clip.x / clip.w + 1) * 0.5 * layout.width,
            (1 - clip.y / clip.w) * 0.5 * layout.height};
}

} // namespace

TEST_CASE("the layout centres the scene and its bands as one group", "[render]") {
    const OverlayRoom room{.top = 30, .right = 100};
    // A wide 2D domain (aspect 4): as wide as the room allows, the bar
    // right beside it, the group centred.
    const FrameLayout wide = layout_frame(640, 360, room, 4.0);
    CHECK(wide.margin == frame_margin(360));
    CHECK(wide.scene.width == Approx(640 - 100 - 2 * wide.margin));
    CHECK(wide.scene.height == Approx(wide.scene.width / 4));
    CHECK(wide.scene.x == Approx(wide.margin));
    CHECK(wide.right.x == Approx(wide.scene.right()));
    CHECK(wide.right.right() == Approx(640 - wide.margin));
    CHECK(wide.top.bottom() == Approx(wide.scene.y));
    CHECK(0.5 * (wide.top.y + wide.scene.bottom()) == Approx(180));
    // A tall one (aspect 0.5): as tall as the room allows, no dead band
    // between the scene and the bar, equal margins left and right.
    const FrameLayout tall = layout_frame(640, 360, room, 0.5);
    CHECK(tall.scene.height == Approx(360 - 30 - 2 * tall.margin));
    CHECK(tall.scene.width == Approx(0.5 * tall.scene.height));
    CHECK(tall.right.x == Approx(tall.scene.right()));
    CHECK(tall.scene.x == Approx(640 - tall.right.right()));
    // 3D (no aspect of its own): the scene fills the room.
    const FrameLayout free = layout_frame(640, 360, room, 0);
    CHECK(free.scene.width == Approx(640 - 100 - 2 * free.margin));
    CHECK(free.scene.height == Approx(360 - 30 - 2 * free.margin));
}

TEST_CASE("the 2D camera fits the domain into the scene's rectangle", "[render]") {
    RenderSettings s;
    s.dimension = 2;
    s.domain_min = {0, 0, 0};
    s.domain_max = {0.1, 0.06, 0};
    const FrameLayout l = layout_frame(320, 180, {.top = 20, .right = 60}, scene_aspect(s));
    const Camera camera = make_camera(s, fixed_pose(s), l);
    CHECK(camera.orthographic);
    const glm::dvec2 lo = pixel(camera, l, s.domain_min), hi = pixel(camera, l, s.domain_max);
    // The domain's corners on the rectangle's: bottom left, top right.
    CHECK(lo.x == Approx(l.scene.x));
    CHECK(lo.y == Approx(l.scene.bottom()));
    CHECK(hi.x == Approx(l.scene.right()));
    CHECK(hi.y == Approx(l.scene.y));
}

TEST_CASE("the 3D camera looks at its target, centred in the scene's rectangle", "[render]") {
    RenderSettings s;
    s.dimension = 3;
    s.domain_max = glm::dvec3(0.1);
    s.camera_position = {0.3, 0.2, 0.4};
    s.camera_target = {0.05, 0.04, 0.03};
    const FrameLayout l = layout_frame(640, 360, {.top = 20, .right = 80}, 0);
    const Camera camera = make_camera(s, fixed_pose(s), l);
    CHECK_FALSE(camera.orthographic);
    const glm::dvec2 target = pixel(camera, l, s.camera_target);
    CHECK(target.x == Approx(l.scene.x + 0.5 * l.scene.width));
    CHECK(target.y == Approx(l.scene.y + 0.5 * l.scene.height));

    // The target is inside every plane; a point behind the eye is outside
    // the near one, a point far to the left outside the left one.
    const auto planes = view_planes(camera);
    auto distance = [&](int k, const glm::dvec3& p) {
        return glm::dot(planes[std::size_t(k)], glm::dvec4(p - camera.origin, 1.0));
    };
    for (int k = 0; k < 6; ++k)
        CHECK(distance(k, s.camera_target) > 0);
    const glm::dvec3 behind = s.camera_position + (s.camera_position - s.camera_target);
    CHECK(distance(4, behind) < 0);
    const glm::dvec3 right =
        glm::normalize(glm::cross(s.camera_target - s.camera_position, glm::dvec3(0, 1, 0)));
    CHECK(distance(0, s.camera_target - 10.0 * right) < 0);
}
