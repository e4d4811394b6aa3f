#pragma once
// Camera and layout: where the scene, the caption and the colour bar go in
// the image, and the view and projection that put the scene in its place.
// The overlay's room is reserved first (FrameLayout: today fixed shares of
// the image; an overlay that measures its text, or adds a legend, would
// reserve more here), and the camera fits the scene into what is left. A
// camera fitted to the particles or animated over the clip is a different
// CameraPose per frame (today fixed_pose); nothing else changes.

#include "render/render_settings.hpp"

#include <array>
#include <glm/glm.hpp>

namespace sph {

// The room the overlay takes, in pixels, scaled with the image: a caption
// line on top, the colour bar and its labels on the right, a margin around
// the scene.
struct FrameLayout {
    int width = 0, height = 0; // px, the whole image
    float text_scale = 1;      // px per pixel of a glyph
    double bar_space = 0;      // px on the right: the colour bar and its labels
    double margin = 0;         // px around the scene
    double caption_space = 0;  // px on top: the caption
};

FrameLayout layout_frame(int width, int height);

// Where a 3D scene is seen from.
struct CameraPose {
    glm::dvec3 position{0}, target{0}; // m
    double fov = 40;                   // degrees, vertical
};

// The scene's fixed camera (RenderSettings' camera_position, camera_target, fov).
CameraPose fixed_pose(const RenderSettings& settings);

// One frame's transforms. Positions are relative to `origin`, the domain's
// centre: floats stay exact far from the scene's origin.
struct Camera {
    glm::dvec3 origin{0};
    bool orthographic = false; // 2D: looking straight at the plane
    glm::mat4 view{1.f}, projection{1.f};
    int image_height = 0; // px

    // Relative positions to clip space, in double (for culling).
    glm::dmat4 clip_from_world() const { return glm::dmat4(projection * view); }
    // A sphere's image is r * pixels_per_radius() / w pixels across, w its
    // clip-space w (the distance in front of the eye; 1 in 2D).
    double pixels_per_radius() const { return projection[1][1] * image_height; }
};

// 2D: the domain fitted into the scene's part of the layout, orthographic.
// 3D: the pose's perspective, centred in the part left of the colour bar.
Camera make_camera(const RenderSettings& settings, const CameraPose& pose,
                   const FrameLayout& layout);

// The view's six planes (left, right, bottom, top, near, far), each with
// its normal pointing in and normalised, so that a plane's value at a point
// (x, y, z, 1) is the point's distance inside it.
std::array<glm::dvec4, 6> view_planes(const Camera& camera);

} // namespace sph
