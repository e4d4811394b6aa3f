// Camera and layout (src/render/camera.*), without a GL context: the
// overlay's room scales with the image, the 2D camera fits the domain into
// what is left, the 3D camera centres its target left of the colour bar,
// and the view planes measure distances inside the view.
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

TEST_CASE("the overlay's room scales with the image", "[render]") {
    const FrameLayout small = layout_frame(320, 180), hd = layout_frame(1280, 720);
    CHECK(small.text_scale == 1);
    CHECK(small.bar_space == 75);
    CHECK(small.margin == 8);
    CHECK(hd.text_scale == 2);
    CHECK(hd.bar_space == 150);
    CHECK(hd.margin == 24);
    CHECK(hd.caption_space == 2 * small.caption_space);
}

TEST_CASE("the 2D camera fits the domain between the margins, left of the bar", "[render]") {
    RenderSettings s;
    s.dimension = 2;
    s.domain_min = {0, 0, 0};
    s.domain_max = {0.1, 0.06, 0};
    const FrameLayout l = layout_frame(320, 180);
    const Camera camera = make_camera(s, fixed_pose(s), l);
    CHECK(camera.orthographic);
    const glm::dvec2 lo = pixel(camera, l, s.domain_min), hi = pixel(camera, l, s.domain_max);
    // The domain as wide as the room left of the colour bar allows (this one
    // is wider than that room)...
    CHECK(lo.x == Approx(l.margin));
    CHECK(hi.x == Approx(l.width - l.bar_space - l.margin));
    // ... and centred in the room below the caption.
    CHECK(hi.y > l.caption_space + l.margin);
    CHECK(lo.y < l.height - l.margin);
    CHECK(0.5 * (lo.y + hi.y) == Approx(0.5 * (l.caption_space + l.height)));
}

TEST_CASE("the 3D camera looks at its target, centred left of the bar", "[render]") {
    RenderSettings s;
    s.dimension = 3;
    s.domain_max = glm::dvec3(0.1);
    s.camera_position = {0.3, 0.2, 0.4};
    s.camera_target = {0.05, 0.04, 0.03};
    const FrameLayout l = layout_frame(640, 360);
    const Camera camera = make_camera(s, fixed_pose(s), l);
    CHECK_FALSE(camera.orthographic);
    const glm::dvec2 target = pixel(camera, l, s.camera_target);
    CHECK(target.x == Approx(0.5 * (l.width - l.bar_space)));
    CHECK(target.y == Approx(0.5 * l.height));

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
