#include "render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sph {

double frame_margin(int height) {
    return std::max(6.0, std::round(0.03 * height));
}

double scene_aspect(const RenderSettings& s) {
    if (s.dimension != 2)
        return 0;
    const glm::dvec3 size = s.domain_max - s.domain_min;
    return size.y > 0 ? size.x / size.y : 0;
}

FrameLayout layout_frame(int width, int height, const OverlayRoom& room, double aspect) {
    FrameLayout l;
    l.width = width;
    l.height = height;
    l.margin = frame_margin(height);
    const double room_w = std::max(1.0, width - room.right - 2 * l.margin);
    const double room_h = std::max(1.0, height - room.top - 2 * l.margin);
    double w = room_w, h = room_h;
    if (aspect > 0) {
        w = std::min(room_w, room_h * aspect);
        h = w / aspect;
    }
    // The group (scene, the band on its right, the band above) centred.
    const double x = 0.5 * (width - (w + room.right));
    const double y = 0.5 * (height - (h + room.top));
    l.top = {x, y, w + room.right, room.top};
    l.scene = {x, y + room.top, w, h};
    l.right = {x + w, y + room.top, room.right, h};
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
    const PixelRect& r = layout.scene;
    // Clip space of the scene's rectangle to the image's: the rectangle's
    // [-1, 1] square scaled and moved to where the layout puts it.
    const glm::mat4 into_rect =
        glm::translate(glm::mat4(1.f), glm::vec3(float((2 * r.x + r.width) / w - 1),
                                                 float(1 - (2 * r.y + r.height) / h), 0.f)) *
        glm::scale(glm::mat4(1.f), glm::vec3(float(r.width / w), float(r.height / h), 1.f));
    if (camera.orthographic) {
        // The domain fills the rectangle (the layout gave it the domain's
        // aspect; any difference is split evenly).
        const glm::dvec3 size = s.domain_max - s.domain_min;
        const double scale = std::min(r.width / size.x, r.height / size.y); // px per m
        const double half_w = 0.5 * r.width / scale, half_h = 0.5 * r.height / scale;
        const glm::dvec3 centre = 0.5 * (s.domain_min + s.domain_max) - origin;
        const double depth = 10 + 4 * s.radius;
        camera.projection =
            into_rect * glm::mat4(glm::ortho(centre.x - half_w, centre.x + half_w,
                                             centre.y - half_h, centre.y + half_h, -depth, depth));
        return camera;
    }
    camera.view = glm::lookAt(glm::vec3(pose.position - origin), glm::vec3(pose.target - origin),
                              glm::vec3(0, 1, 0));
    // Near enough for a sphere close to the eye, far enough for the whole
    // domain behind the target.
    const double distance = glm::length(pose.position - pose.target);
    const double extent = glm::length(s.domain_max - s.domain_min);
    camera.projection =
        into_rect * glm::perspective(glm::radians(float(pose.fov)), float(r.width / r.height),
                                     float(std::max(1e-4 * distance, 0.01 * s.radius)),
                                     float(4 * (distance + extent)));
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
