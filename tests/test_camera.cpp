// Camera and layout (src/render/camera.*), without a GL context: the layout
// centres the scene and the overlay's bands as one group, the 2D camera fits
// the domain into the scene's rectangle, the 3D camera centres its target
// there, and the view planes measure distances inside the view.
#include "render/camera.hpp"

#include <catch2/catch.hpp>
#include <cmath>

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

namespace {

// A point's place in clip space over w: inside the frame's rectangle when
// both lie within [-1, 1] of the scene's rectangle.
glm::dvec2 in_rect(const Camera& camera, const FrameLayout& l, const glm::dvec3& point) {
    const glm::dvec2 p = pixel(camera, l, point);
    return {2 * (p.x - l.scene.x) / l.scene.width - 1, 1 - 2 * (p.y - l.scene.y) / l.scene.height};
}

RenderSettings tank_3d() {
    RenderSettings s;
    s.dimension = 3;
    s.width = 640;
    s.height = 360;
    s.domain_min = glm::dvec3(0);
    s.domain_max = {0.4, 0.25, 0.1};
    s.radius = 0.002;
    s.camera_fixed = false;
    s.frame_to_domain = true;
    s.fps = 10;
    s.duration = 1;
    return s;
}

// Points of a box's corners and its centre, as a snapshot.
Snapshot box_points(int dimension, const glm::dvec3& lo, const glm::dvec3& hi,
                    std::uint64_t frame) {
    Snapshot snap;
    snap.dimension = dimension;
    snap.frame = frame;
    const int n = dimension == 3 ? 8 : 4;
    for (int k = 0; k <= n; ++k) {
        const glm::dvec3 p =
            k == n ? 0.5 * (lo + hi)
                   : glm::dvec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        for (int a = 0; a < dimension; ++a)
            snap.position.push_back(p[a]);
        snap.density.push_back(1000);
    }
    snap.velocity.assign(snap.position.size(), 0);
    return snap;
}

// The largest |x| and |y| of the box's corners in the rectangle's [-1, 1].
glm::dvec2 reach(const Camera& camera, const FrameLayout& l, const glm::dvec3& lo,
                 const glm::dvec3& hi) {
    glm::dvec2 most(0);
    for (int k = 0; k < 8; ++k)
        most = glm::max(
            most, glm::abs(in_rect(
                      camera, l, {k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z})));
    return most;
}

} // namespace

TEST_CASE("fit domain: the 3D tank fills its rectangle, the bar right beside it", "[render]") {
    // The complaint: the tank took 55% of the width, a dead band
    // before the colour bar. Now the rectangle takes the tank's aspect and
    // the tank reaches 97% of it (the margin) on one axis, 90% or more on the other.
    const RenderSettings s = tank_3d();
    const FrameLayout l = layout_for(s, {.top = 20, .right = 80});
    CameraRig rig(s, l.scene.width / l.scene.height);
    const CameraPose pose = rig.pose(box_points(3, glm::dvec3(0.01), glm::dvec3(0.05), 0));
    const Camera camera = make_camera(s, pose, l);
    const glm::dvec2 most = reach(camera, l, s.domain_min, s.domain_max);
    CHECK(std::max(most.x, most.y) == Approx(0.97).margin(0.005));
    CHECK(std::min(most.x, most.y) > 0.9);
    CHECK(most.x <= 0.975);
    CHECK(most.y <= 0.975);
    CHECK(l.right.x == Approx(l.scene.right()));
    CHECK(l.scene.width < 640 - 80);
}

TEST_CASE("a fixed 3D camera, distant or close, leaves no dead band beside the tank", "[render]") {
    // Was: the rectangle took the default camera's view of the domain, so a
    // distant camera (the README's first clip) left bands at both sides of
    // the tank and a close one cut the tank off in a narrow rectangle.
    RenderSettings s = tank_3d();
    s.camera_fixed = true;
    s.camera_target = 0.5 * (s.domain_min + s.domain_max);
    const OverlayRoom room{.top = 20, .right = 80};
    const FrameLayout whole = layout_frame(s.width, s.height, room);
    struct Case {
        const char* name;
        glm::dvec3 position;
        double fov;
    };
    for (const Case& c :
         {Case{"distant, from the side", {1.2, 0.6, -0.9}, 40},
          Case{"distant, end on", {0.2, 0.3, 1.5}, 30}, Case{"close-up", {0.25, 0.15, 0.3}, 40}}) {
        INFO(c.name);
        s.camera_position = c.position;
        s.fov = c.fov;
        const FrameLayout l = layout_for(s, room);
        CameraRig rig(s, l.scene.width / l.scene.height);
        const Camera camera =
            make_camera(s, rig.pose(box_points(3, s.domain_min, s.domain_max, 0)), l);
        const glm::dvec2 most = reach(camera, l, s.domain_min, s.domain_max);
        if (most.y > 1) {
            // Cut off above and below: the room is the scene's, whole.
            CHECK(l.scene.width == Approx(whole.scene.width));
            CHECK(l.scene.height == Approx(whole.scene.height));
            CHECK(most.x > 1);
        } else {
            // The tank's image reaches the rectangle's sides (the 3% margin).
            CHECK(most.x == Approx(0.97).margin(0.002));
        }
        // The bar right beside the scene, the group centred.
        CHECK(l.right.x == Approx(l.scene.right()));
        CHECK(l.scene.x - 0 == Approx(s.width - l.right.right()).margin(1));
    }
}

TEST_CASE("fit fluid and follow frame the fluid, not the tank", "[render]") {
    RenderSettings s = tank_3d();
    s.fluid_min = glm::dvec3(0);
    s.fluid_max = {0.06, 0.11, 0.1};
    const FrameLayout l = layout_for(s, {.top = 20, .right = 80});
    const double aspect = l.scene.width / l.scene.height;
    for (const char* fit : {"fluid", "follow"}) {
        INFO(fit);
        s.camera_fit = *choice_named<CameraFit>(fit);
        CameraRig rig(s, aspect);
        const CameraPose pose = rig.pose(box_points(3, s.fluid_min, s.fluid_max, 0));
        const Camera camera = make_camera(s, pose, l);
        const glm::dvec2 most = reach(camera, l, s.fluid_min, s.fluid_max);
        CHECK(std::max(most.x, most.y) > 0.8);
        CHECK(std::max(most.x, most.y) < 0.97);
        // The tank's far corner is out of view: the camera came closer.
        CHECK(std::max(std::abs(in_rect(camera, l, s.domain_max).x),
                       std::abs(in_rect(camera, l, s.domain_max).y)) > 1);
    }
}

TEST_CASE("2D fits: the domain whole, or the fluid's region inside it", "[render]") {
    RenderSettings s;
    s.dimension = 2;
    s.domain_max = {0.4, 0.25, 0};
    s.radius = 0.001;
    const double aspect = 1.6;
    const CameraPose whole = fit_region(s.domain_min, s.domain_max, aspect, s);
    CHECK(whole.height == 0.25);
    CHECK(whole.target.x == 0.2);
    CHECK(whole.target.y == 0.125);
    // A column in the left corner: a region of the column's height, kept
    // inside the domain (its left edge on the wall), holding the column.
    const CameraPose column = fit_region({0, 0, 0}, {0.06, 0.12, 0}, aspect, s);
    CHECK(column.height == Approx(0.12));
    CHECK(column.target.x - 0.5 * aspect * column.height == Approx(0).margin(1e-12));
    CHECK(column.target.y - 0.5 * column.height == Approx(0).margin(1e-12));
    // A layer wider than the frame's aspect allows: as wide as the domain.
    const CameraPose layer = fit_region({0, 0, 0}, {0.4, 0.05, 0}, aspect, s);
    CHECK(layer.height == Approx(0.25));
    // Drawn: the region fills the rectangle.
    const FrameLayout l = layout_frame(320, 200, {}, aspect);
    const Camera camera = make_camera(s, column, l);
    const glm::dvec2 corner = in_rect(camera, l, {0.06 * 0 + aspect * 0.12, 0.12, 0});
    CHECK(corner.x == Approx(1));
    CHECK(corner.y == Approx(1));
}

TEST_CASE("follow keeps every point in view and moves without jumps", "[render]") {
    FollowedBounds bounds(0.5);
    const double dt = 1.0 / 30;
    double previous_hi = 0;
    for (int k = 0; k < 90; ++k) {
        const double t = k * dt;
        // A splash: the points' top rises fast for 1 s, then falls back at
        // once to 0.1 (a drop rejoining the pool), with noise on top.
        const double noise = 0.002 * std::sin(37.0 * k);
        const double top = (t < 1 ? 0.1 + 0.3 * t : 0.1) + noise;
        bounds.update({0, 0, 0}, {0.2, top, 0}, t);
        // Containment, always.
        CHECK(bounds.hi().y >= top);
        CHECK(bounds.lo().y <= 0);
        if (t > 1 + dt) {
            // Narrowing is smooth: each step at most the lag's share of the gap.
            const double step = previous_hi - bounds.hi().y;
            CHECK(step <= (1 - std::exp(-dt / 0.5)) * (previous_hi - 0.098) + 1e-12);
            CHECK(step >= -0.0041); // the noise may widen it, by at most its swing
        }
        previous_hi = bounds.hi().y;
    }
    // Three time constants after the fall, close to the points again.
    CHECK(bounds.hi().y < 0.1 + 0.3 * std::exp(-1.9 / 0.5) + 0.01);
}

TEST_CASE("follow's camera never cuts a particle off (2D and 3D)", "[render]") {
    for (int dimension : {2, 3}) {
        INFO(dimension << "D");
        RenderSettings s = tank_3d();
        s.dimension = dimension;
        s.frame_to_domain = dimension == 3;
        if (dimension == 2)
            s.domain_max.z = 0;
        s.camera_fit = CameraFit::follow;
        const FrameLayout l = layout_for(s, {.top = 20, .right = 80});
        CameraRig rig(s, l.scene.width / l.scene.height);
        for (std::uint64_t k = 0; k < 20; ++k) {
            // A box that slides and grows and shrinks.
            const double t = double(k) / s.fps;
            const glm::dvec3 lo(0.15 * t, 0, 0);
            const glm::dvec3 hi = lo + glm::dvec3(0.05 + 0.2 * std::sin(3 * t) * std::sin(3 * t),
                                                  0.1 * (1 + std::cos(5 * t)) + 0.01, 0.1);
            const Snapshot snap = box_points(dimension, lo, glm::min(hi, s.domain_max), k);
            const Camera camera = make_camera(s, rig.pose(snap), l);
            for (std::size_t i = 0; i < snap.size(); ++i) {
                glm::dvec3 p(0);
                for (int a = 0; a < dimension; ++a)
                    p[a] = snap.position[i * std::size_t(dimension) + std::size_t(a)];
                const glm::dvec2 at = in_rect(camera, l, p);
                CHECK(std::abs(at.x) <= 1 + 1e-6); // at a wall: on the edge
                CHECK(std::abs(at.y) <= 1 + 1e-6);
            }
        }
    }
}

TEST_CASE("a camera path passes through its keyframes, smoothly between", "[render]") {
    using Key = RenderSettings::CameraKeyframe;
    std::vector<Key> path(3);
    path[0] = {.time = 0, .position = {1, 0.5, 1}, .target = {0, 0, 0}, .fov = 40};
    path[1] = {.time = 1, .position = {0, 0.8, 1.5}, .target = {0.1, 0, 0}, .fov = 30};
    path[2] = {.time = 3, .position = {-1, 0.5, 0.5}, .target = {0.2, 0.1, 0}, .fov = 50};
    for (const Key& key : path) {
        const CameraPose at = path_pose(path, key.time, 3);
        CHECK(at.position == key.position);
        CHECK(at.target == key.target);
        CHECK(at.fov == key.fov);
    }
    // Held before the first and after the last.
    CHECK(path_pose(path, -1, 3).position == path[0].position);
    CHECK(path_pose(path, 9, 3).position == path[2].position);
    // Continuous in value and slope through the middle keyframe (C1).
    const double e = 1e-6;
    const glm::dvec3 left = path_pose(path, 1 - e, 3).position,
                     right = path_pose(path, 1 + e, 3).position;
    CHECK(glm::length(left - path[1].position) < 1e-5);
    const glm::dvec3 slope_left = (path[1].position - left) / e,
                     slope_right = (right - path[1].position) / e;
    CHECK(glm::length(slope_left - slope_right) < 1e-4);
    // The Catmull-Rom tangent there: (p2 - p0) / (t2 - t0).
    const glm::dvec3 tangent = (path[2].position - path[0].position) / 3.0;
    CHECK(glm::length(slope_right - tangent) < 1e-4);
    // fov interpolated in log stays between its keyframes' here.
    const double fov = path_pose(path, 0.5, 3).fov;
    CHECK(fov > 29);
    CHECK(fov < 41);
    // 2D: centre and height.
    std::vector<Key> flat(2);
    flat[0] = {.time = 0, .target = {0.1, 0.1, 0}, .height = 0.2};
    flat[1] = {.time = 2, .target = {0.3, 0.1, 0}, .height = 0.1};
    const CameraPose mid = path_pose(flat, 1, 2);
    CHECK(mid.target.x == Approx(0.2));
    CHECK(mid.height == Approx(std::sqrt(0.2 * 0.1)));
    CHECK(path_pose(flat, 2, 2).height == 0.1);
}

TEST_CASE("an orbit circles the fit's target at one distance, the tank in view", "[render]") {
    RenderSettings s = tank_3d();
    s.orbit = RenderSettings::Orbit{.turns = 1, .elevation_deg = 25, .start_deg = 30};
    const FrameLayout l = layout_for(s, {.top = 20, .right = 80});
    CameraRig rig(s, l.scene.width / l.scene.height);
    const glm::dvec3 centre = 0.5 * (s.domain_min + s.domain_max);
    double distance = 0;
    for (std::uint64_t k = 0; k <= 10; ++k) {
        const CameraPose pose = rig.pose(box_points(3, glm::dvec3(0.01), glm::dvec3(0.05), k));
        CHECK(pose.target == centre);
        const double d = glm::length(pose.position - pose.target);
        if (k == 0)
            distance = d;
        CHECK(d == Approx(distance));
        // 25 degrees above the target.
        CHECK((pose.position.y - centre.y) / d == Approx(std::sin(glm::radians(25.0))));
        const glm::dvec2 most = reach(make_camera(s, pose, l), l, s.domain_min, s.domain_max);
        CHECK(most.x <= 0.98);
        CHECK(most.y <= 0.98);
        const glm::dvec3 from = glm::normalize(pose.position - centre);
        const glm::dvec3 expected = view_direction(30 + 360.0 * double(k) / 10, 25);
        CHECK(glm::length(from - expected) < 1e-9);
    }
}
