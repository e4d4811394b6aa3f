#pragma once
// Camera and layout: where the scene, the caption and the colour bar go in
// the image, and the view and projection that put the scene in its place.
// The overlay measures its text and asks for its room (OverlayRoom), the
// layout places the scene and the bands (FrameLayout), and the camera fits
// the scene into its rectangle. A camera fitted to the particles or
// animated over the clip is a different CameraPose per frame; nothing else
// changes.

#include "render/render_settings.hpp"

#include <array>
#include <glm/glm.hpp>

namespace sph {

// A rectangle of the image in pixels, origin at the top left, y down.
struct PixelRect {
    double x = 0, y = 0, width = 0, height = 0;
    double right() const { return x + width; }
    double bottom() const { return y + height; }
};

// The room the overlay asks for beside the scene, px: a band above it (the
// title and caption) and one on its right (the colour bar and its labels).
struct OverlayRoom {
    double top = 0, right = 0;
};

// Where the scene and the overlay's bands go. The scene and its bands are
// one group, centred in the image with at least `margin` around it: the bar
// sits right beside the scene, with no dead band between them.
struct FrameLayout {
    int width = 0, height = 0; // px, the whole image
    double margin = 0;         // px, at least, around the group
    PixelRect scene;           // where the scene is drawn
    PixelRect top, right;      // the overlay's bands
};

// The margin around the group for an image `height` px tall.
double frame_margin(int height);

// The scene's own aspect (width / height) for the layout: 2D the domain's,
// 3D none (0).
double scene_aspect(const RenderSettings& settings);

// `aspect`: the scene's own width / height (2D: the domain's), which the
// scene's rectangle keeps; 0: the scene fills the room left (3D).
FrameLayout layout_frame(int width, int height, const OverlayRoom& room = {}, double aspect = 0);

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

// 2D: the domain fitted into the layout's scene rectangle, orthographic.
// 3D: the pose's perspective, its vertical field of view the scene
// rectangle's height, centred in it.
Camera make_camera(const RenderSettings& settings, const CameraPose& pose,
                   const FrameLayout& layout);

// The view's six planes (left, right, bottom, top, near, far), each with
// its normal pointing in and normalised, so that a plane's value at a point
// (x, y, z, 1) is the point's distance inside it.
std::array<glm::dvec4, 6> view_planes(const Camera& camera);

} // namespace sph
