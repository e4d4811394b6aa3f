#pragma once
// Camera and layout: where the scene, the caption and the colour bar go in
// the image, and the view and projection that put the scene in its place.
// The overlay measures its text and asks for its room (OverlayRoom), the
// layout places the scene and the bands (FrameLayout), and the camera fits
// the scene into its rectangle. A camera fitted to the particles or
// animated over the clip is a different CameraPose per frame; nothing else
// changes.

#include "render/render_settings.hpp"
#include "sph/snapshot.hpp"

#include <array>
#include <glm/glm.hpp>
#include <vector>

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
    // The scene's width / height as asked for (else as it came out): what
    // render.camera.aspect reproduces.
    double aspect = 0;
};

// The margin around the group for an image `height` px tall.
double frame_margin(int height);

// The scene's own aspect (width / height) for the layout: 2D the domain's,
// 3D none (0).
double scene_aspect(const RenderSettings& settings);

// `aspect`: the scene's own width / height (2D: the domain's), which the
// scene's rectangle keeps; 0: the scene fills the room left (3D).
FrameLayout layout_frame(int width, int height, const OverlayRoom& room = {}, double aspect = 0);

// Where the scene is seen from. 3D: position, target, up and fov; 2D: the
// region of the plane in view, centred on target (x, y), `height` tall
// (0: the domain fitted).
struct CameraPose {
    glm::dvec3 position{0}, target{0}; // m
    glm::dvec3 up{0, 1, 0};
    double fov = 40;   // degrees, vertical
    double height = 0; // m, 2D
};

// The scene's fixed camera (RenderSettings' camera_position, camera_target,
// camera_up, fov and view_height).
CameraPose fixed_pose(const RenderSettings& settings);

// The direction from the target to the default camera: 30 degrees round
// from +z towards +x, 20 degrees above the horizontal.
glm::dvec3 view_direction(double azimuth_deg, double elevation_deg);
glm::dvec3 default_view_direction();

// 3D: the pose from `direction` (target to eye) at which the box [lo, hi]
// fills a frame of `aspect` (width / height) at `fov` with a 3% margin, the
// nearest such distance. `centre`: the target moved across the view so the
// box's image is centred; else the box's centre.
CameraPose fit_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& direction,
                   const glm::dvec3& up, double fov, double aspect, bool centre = true);

// 3D: the aspect (width / height) of the box's image from `pose`, taken
// symmetric about the view's axis.
double image_aspect(const glm::dvec3& lo, const glm::dvec3& hi, const CameraPose& pose);

// 3D: the aspect (width / height) of a frame at the pose's fov that is as
// wide as the box's image (symmetric about the view's axis, with fit_box's
// 3% margin): beside it nothing is dead. 0 where the box fills the frame
// whole: wider than `room_aspect` and taller than the view, or round the
// eye (a corner behind it).
double width_aspect(const glm::dvec3& lo, const glm::dvec3& hi, const CameraPose& pose,
                    double room_aspect);

// 2D: the region of the plane that shows the box [lo, hi] whole in a frame
// of `aspect`, kept inside the domain where it is smaller than the domain
// and never larger than the domain fitted.
CameraPose fit_region(const glm::dvec3& lo, const glm::dvec3& hi, double aspect,
                      const RenderSettings& settings);

// The camera along a path at time t (s): cubic Hermite between keyframes,
// with Catmull-Rom tangents for uneven times, (p[k+1] - p[k-1]) / (t[k+1] -
// t[k-1]), one-sided at the ends; fov and height in log so they stay
// positive. Exactly a keyframe at its time; held before the first and after
// the last.
CameraPose path_pose(const std::vector<RenderSettings::CameraKeyframe>& path, double t,
                     int dimension);

// Bounds that follow a moving set of points without jitter and without
// losing any: they widen at once to take in every point and narrow towards
// the points' bounds exponentially, with time constant `tau` (s).
class FollowedBounds {
  public:
    explicit FollowedBounds(double tau = 0.5) : tau_(tau) {}
    void update(const glm::dvec3& lo, const glm::dvec3& hi, double time);
    const glm::dvec3& lo() const { return lo_; }
    const glm::dvec3& hi() const { return hi_; }

  private:
    double tau_;
    bool started_ = false;
    double time_ = 0;
    glm::dvec3 lo_{0}, hi_{0};
};

// Each frame's pose from the settings: fixed, fitted (domain, fluid,
// follow), along a path or round an orbit. Frames come in order (follow
// keeps the bounds of the frames before).
class CameraRig {
  public:
    // `aspect`: the scene rectangle's width / height.
    CameraRig(const RenderSettings& settings, double aspect);
    CameraPose pose(const Snapshot& frame);

  private:
    CameraPose fitted(const glm::dvec3& lo, const glm::dvec3& hi, bool pad, double time) const;
    const RenderSettings& settings_;
    double aspect_;
    FollowedBounds followed_;
};

// The layout for the settings, one for the clip: 2D the domain's aspect;
// 3D with frame_to_domain: a given scene_aspect; for a fixed camera or a
// path, width_aspect of the domain from it (a path's widest, sampled over
// the clip), so a close or distant camera leaves no dead band beside the
// tank; for fitted cameras and orbits, which fit themselves into the
// rectangle, the domain's image from the default camera (fov 40, so that
// the layout does not move with a camera's fov); else the room.
FrameLayout layout_for(const RenderSettings& settings, const OverlayRoom& room);

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
