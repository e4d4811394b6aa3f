#include "render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sph {

FrameLayout layout_frame(int width, int height) {
    FrameLayout l;
    l.width = width;
    l.height = height;
    l.text_scale = std::max(1.f, std::round(float(height) / 360.f));
    l.bar_space = std::max(75.0, 150.0 * width / 1280.0);
    l.margin = std::max(8.0, 24.0 * height / 720.0);
    l.caption_space = 18.0 * l.text_scale;
    return l;
}

CameraPose fixed_pose(const RenderSettings& settings) {
    return {settings.camera_position, settings.camera_target, settings.fov};
}

Camera make_camera(const RenderSettings& s, const CameraPose& pose, const FrameLayout& layout) {
    Camera camera;
    camera.origin = 0.5 * (s.domain_min + s.domain_max);
    camera.orthographic = s.dimension == 2;
    camera.image_height = layout.height;
    const glm::dvec3& origin = camera.origin;
    const int w = layout.width, h = layout.height;
    if (camera.orthographic) {
        // The domain as large as fits between the margins, left of the bar
        // and below the caption, centred there.
        const glm::dvec3 size = s.domain_max - s.domain_min;
        const double available_w = std::max(1.0, w - layout.bar_space - 2 * layout.margin);
        const double available_h = std::max(1.0, h - layout.caption_space - 2 * layout.margin);
        const double scale = std::min(available_w / size.x, available_h / size.y); // px per m
        const double left = s.domain_min.x - origin.x -
                            (layout.margin + 0.5 * (available_w - scale * size.x)) / scale;
        const double bottom = s.domain_min.y - origin.y -
                              (layout.margin + 0.5 * (available_h - scale * size.y)) / scale;
        const double depth = 10 + 4 * s.radius;
        camera.projection =
            glm::ortho(left, left + w / scale, bottom, bottom + h / scale, -depth, depth);
        return camera;
    }
    camera.view = glm::lookAt(glm::vec3(pose.position - origin), glm::vec3(pose.target - origin),
                              glm::vec3(0, 1, 0));
    // Near enough for a sphere close to the eye, far enough for the whole
    // domain behind the target.
    const double distance = glm::length(pose.position - pose.target);
    const double extent = glm::length(s.domain_max - s.domain_min);
    camera.projection = glm::perspective(glm::radians(float(pose.fov)), float(w) / float(h),
                                         float(std::max(1e-4 * distance, 0.01 * s.radius)),
                                         float(4 * (distance + extent)));
    // Centre the view in the part of the image left of the colour bar.
    camera.projection =
        glm::translate(glm::mat4(1.f), glm::vec3(float(-layout.bar_space / w), 0.f, 0.f)) *
        camera.projection;
    return camera;
}

std::array<glm::dvec4, 6> view_planes(const Camera& camera) {
    // From the clip matrix's rows (Gribb and Hartmann 2001, "Fast extraction
    // of viewing frustum planes from the world-view-projection matrix"):
    // w + x, w - x, w + y, w - y, w + z, w - z, each >= 0 inside.
    const glm::dmat4 clip = camera.clip_from_world();
    auto row = [&clip](int r) {
        return glm::dvec4(clip[0][r], clip[1][r], clip[2][r], clip[3][r]);
    };
    std::array<glm::dvec4, 6> planes;
    for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
            const glm::dvec4 plane = row(3) + (side ? -1.0 : 1.0) * row(a);
            planes[std::size_t(2 * a + side)] = plane / glm::length(glm::dvec3(plane));
        }
    return planes;
}

} // namespace sph
