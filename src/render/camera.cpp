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
    l.aspect = aspect > 0 ? aspect : w / h;
    return l;
}

CameraPose fixed_pose(const RenderSettings& settings) {
    return {settings.camera_position, settings.camera_target, settings.camera_up, settings.fov,
            settings.dimension == 2 ? settings.view_height : 0};
}

glm::dvec3 view_direction(double azimuth_deg, double elevation_deg) {
    const double az = glm::radians(azimuth_deg), el = glm::radians(elevation_deg);
    return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

glm::dvec3 default_view_direction() {
    return view_direction(30, 20);
}

namespace {

// The view's axes: right, up in the image, and back (target to eye).
struct ViewBasis {
    glm::dvec3 right, up, back;
};

ViewBasis basis(const glm::dvec3& back, const glm::dvec3& up) {
    ViewBasis b;
    b.back = glm::normalize(back);
    b.right = glm::normalize(glm::cross(up, b.back));
    b.up = glm::cross(b.back, b.right);
    return b;
}

std::array<glm::dvec3, 8> corners(const glm::dvec3& lo, const glm::dvec3& hi) {
    std::array<glm::dvec3, 8> c;
    for (int k = 0; k < 8; ++k)
        c[std::size_t(k)] = {k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
    return c;
}

// A corner's image, as tangents of its angles off the view's axis, from an
// eye `distance` behind `target`.
glm::dvec2 tangents(const glm::dvec3& corner, const glm::dvec3& target, double distance,
                    const ViewBasis& b) {
    const glm::dvec3 p = corner - target;
    const double depth = distance - glm::dot(p, b.back);
    return glm::dvec2(glm::dot(p, b.right), glm::dot(p, b.up)) / depth;
}

// Of the box's image fitting the frame, the margin: 3% of each half.
constexpr double fit_margin = 0.97;

} // namespace

CameraPose fit_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& direction,
                   const glm::dvec3& up, double fov, double aspect, bool centre) {
    const ViewBasis b = basis(direction, up);
    const double tv = fit_margin * std::tan(glm::radians(0.5 * fov));
    const double th = tv * aspect;
    const auto box = corners(lo, hi);
    // A corner at p from the target is in view at distance D when
    // |p.right| <= th (D - p.back) and |p.up| <= tv (D - p.back).
    auto nearest = [&](const glm::dvec3& target) {
        double d = 1e-9 + 1e-3 * glm::length(hi - lo);
        for (const glm::dvec3& c : box) {
            const glm::dvec3 p = c - target;
            d = std::max(
                d, std::max(std::abs(glm::dot(p, b.right)) / th, std::abs(glm::dot(p, b.up)) / tv) +
                       glm::dot(p, b.back));
        }
        return d;
    };
    glm::dvec3 target = 0.5 * (lo + hi);
    if (centre)
        // Seen from aside, the box's centre is not its image's: move the
        // target across the view by the image's offset, a few times over.
        for (int pass = 0; pass < 4; ++pass) {
            const double d = nearest(target);
            glm::dvec2 low(1e300), high(-1e300);
            for (const glm::dvec3& c : box) {
                const glm::dvec2 t = tangents(c, target, d, b);
                low = glm::min(low, t);
                high = glm::max(high, t);
            }
            const glm::dvec2 offset = 0.5 * (low + high);
            target += d * (offset.x * b.right + offset.y * b.up);
        }
    const double d = nearest(target);
    CameraPose pose;
    pose.target = target;
    pose.position = target + d * b.back;
    pose.up = up;
    pose.fov = fov;
    return pose;
}

double image_aspect(const glm::dvec3& lo, const glm::dvec3& hi, const CameraPose& pose) {
    const ViewBasis b = basis(pose.position - pose.target, pose.up);
    const double distance = glm::length(pose.position - pose.target);
    glm::dvec2 extent(0);
    for (const glm::dvec3& c : corners(lo, hi))
        extent = glm::max(extent, glm::abs(tangents(c, pose.target, distance, b)));
    return extent.y > 0 ? extent.x / extent.y : 0;
}

double width_aspect(const glm::dvec3& lo, const glm::dvec3& hi, const CameraPose& pose,
                    double room_aspect) {
    const ViewBasis b = basis(pose.position - pose.target, pose.up);
    const double distance = glm::length(pose.position - pose.target);
    const double tv = std::tan(glm::radians(0.5 * pose.fov));
    glm::dvec2 extent(0);
    for (const glm::dvec3& c : corners(lo, hi)) {
        if (!(distance - glm::dot(c - pose.target, b.back) > 1e-9 * distance))
            return 0;
        extent = glm::max(extent, glm::abs(tangents(c, pose.target, distance, b)));
    }
    const double aspect = extent.x / (fit_margin * tv);
    // A close-up: cut off at the top and bottom, and wider than the room.
    if (aspect >= room_aspect && extent.y > tv)
        return 0;
    return aspect;
}

CameraPose fit_region(const glm::dvec3& lo, const glm::dvec3& hi, double aspect,
                      const RenderSettings& s) {
    const glm::dvec3 domain = s.domain_max - s.domain_min;
    const double whole = std::max(domain.y, domain.x / aspect);
    CameraPose pose;
    pose.target = 0.5 * (s.domain_min + s.domain_max);
    pose.target.z = 0;
    pose.fov = s.fov;
    pose.height = whole;
    const double height = std::max(hi.y - lo.y, (hi.x - lo.x) / aspect);
    if (!(height < whole))
        return pose;
    pose.height = height;
    // Inside the domain on each axis where the view is narrower than it.
    const glm::dvec2 half(0.5 * height * aspect, 0.5 * height);
    for (int a = 0; a < 2; ++a) {
        const double c = 0.5 * (lo[a] + hi[a]);
        pose.target[a] = 2 * half[a] <= domain[a]
                             ? std::clamp(c, s.domain_min[a] + half[a], s.domain_max[a] - half[a])
                             : pose.target[a];
    }
    return pose;
}

CameraPose path_pose(const std::vector<RenderSettings::CameraKeyframe>& path, double t,
                     int dimension) {
    using Key = RenderSettings::CameraKeyframe;
    auto keyframe = [dimension](const Key& k) {
        CameraPose pose;
        pose.position = k.position;
        pose.target = k.target;
        pose.up = k.up;
        pose.fov = k.fov;
        pose.height = dimension == 2 ? k.height : 0;
        return pose;
    };
    if (!(t > path.front().time))
        return keyframe(path.front());
    if (!(t < path.back().time))
        return keyframe(path.back());
    std::size_t k = 0;
    while (path[k + 1].time <= t)
        ++k;
    if (t == path[k].time)
        return keyframe(path[k]);
    const std::size_t n = path.size();
    const double dt = path[k + 1].time - path[k].time;
    const double s = (t - path[k].time) / dt;
    const double h00 = (2 * s - 3) * s * s + 1, h10 = ((s - 2) * s + 1) * s;
    const double h01 = (3 - 2 * s) * s * s, h11 = (s - 1) * s * s;
    // The tangent (per second) at keyframe j of the value f picks.
    auto tangent = [&](std::size_t j, auto f) {
        const std::size_t a = j == 0 ? 0 : j - 1, b = std::min(j + 1, n - 1);
        return (f(path[b]) - f(path[a])) / (path[b].time - path[a].time);
    };
    auto hermite = [&](auto f) {
        return h00 * f(path[k]) + h10 * dt * tangent(k, f) + h01 * f(path[k + 1]) +
               h11 * dt * tangent(k + 1, f);
    };
    CameraPose pose;
    pose.position = hermite([](const Key& key) { return key.position; });
    pose.target = hermite([](const Key& key) { return key.target; });
    pose.up = glm::normalize(hermite([](const Key& key) { return key.up; }));
    pose.fov = std::min(179.0, std::exp(hermite([](const Key& key) { return std::log(key.fov); })));
    if (dimension == 2)
        pose.height = std::exp(hermite([](const Key& key) { return std::log(key.height); }));
    return pose;
}

void FollowedBounds::update(const glm::dvec3& lo, const glm::dvec3& hi, double time) {
    if (!started_) {
        started_ = true;
        lo_ = lo;
        hi_ = hi;
        time_ = time;
        return;
    }
    // Narrowing: a first-order lag towards the points' bounds; widening at once.
    const double keep = std::exp(-std::max(0.0, time - time_) / tau_);
    time_ = time;
    for (int a = 0; a < 3; ++a) {
        lo_[a] = lo[a] < lo_[a] ? lo[a] : lo[a] + keep * (lo_[a] - lo[a]);
        hi_[a] = hi[a] > hi_[a] ? hi[a] : hi[a] + keep * (hi_[a] - hi[a]);
    }
}

CameraRig::CameraRig(const RenderSettings& settings, double aspect)
    : settings_(settings), aspect_(aspect > 0 ? aspect : 1) {}

CameraPose CameraRig::pose(const Snapshot& frame) {
    const RenderSettings& s = settings_;
    // Frames are k / fps apart: the camera moves smoothly even where the
    // simulation's time steps do not land on a frame's time. A last frame
    // between two (at the duration, cli/clip_run.cpp) is at the duration.
    double time = s.fps > 0 ? double(frame.frame) / s.fps : double(frame.time);
    if (s.fps > 0 && s.duration > 0)
        time = std::min(time, s.duration);
    if (!s.camera_path.empty())
        return path_pose(s.camera_path, time, s.dimension);
    if (s.camera_fixed)
        return fixed_pose(s);
    if (s.camera_fit == CameraFit::fluid)
        return fitted(s.fluid_min, s.fluid_max, true, time);
    if (s.camera_fit == CameraFit::follow) {
        glm::dvec3 lo(1e300), hi(-1e300);
        const int d = frame.dimension;
        for (std::size_t i = 0; i < frame.size(); ++i)
            for (int a = 0; a < d; ++a) {
                const double x = frame.position[i * std::size_t(d) + std::size_t(a)];
                lo[a] = std::min(lo[a], x);
                hi[a] = std::max(hi[a], x);
            }
        for (int a = d; a < 3; ++a)
            lo[a] = hi[a] = 0;
        if (frame.size() == 0) {
            lo = s.domain_min;
            hi = s.domain_max;
        }
        followed_.update(lo, hi, time);
        return fitted(followed_.lo(), followed_.hi(), true, time);
    }
    return fitted(s.domain_min, s.domain_max, false, time);
}

CameraPose CameraRig::fitted(const glm::dvec3& box_lo, const glm::dvec3& box_hi, bool pad,
                             double time) const {
    const RenderSettings& s = settings_;
    glm::dvec3 lo = box_lo, hi = box_hi;
    if (pad) {
        // The spheres' radius, and a little room round the fluid.
        const glm::dvec3 size = hi - lo;
        const double room = 2 * s.radius + 0.04 * std::max({size.x, size.y, size.z});
        for (int a = 0; a < s.dimension; ++a) {
            lo[a] -= room;
            hi[a] += room;
        }
    }
    if (s.dimension == 2) {
        CameraPose pose = fit_region(lo, hi, aspect_, s);
        if (s.centre_given)
            pose.target = s.camera_target;
        if (s.view_height > 0)
            pose.height = s.view_height;
        return pose;
    }
    if (s.orbit) {
        const RenderSettings::Orbit& o = *s.orbit;
        const double turned = s.duration > 0 ? time / s.duration : 0;
        const glm::dvec3 back =
            view_direction(o.start_deg + 360 * o.turns * turned, o.elevation_deg);
        CameraPose pose;
        pose.target = s.target_given ? s.camera_target : 0.5 * (lo + hi);
        pose.up = s.camera_up;
        pose.fov = s.fov;
        double distance = o.distance;
        if (!(distance > 0))
            // The nearest distance from which the box fills the frame from
            // every azimuth: the camera does not breathe in and out.
            for (int k = 0; k < 36; ++k) {
                const CameraPose from = fit_box(lo, hi, view_direction(10.0 * k, o.elevation_deg),
                                                s.camera_up, s.fov, aspect_, false);
                distance = std::max(distance, glm::length(from.position - from.target));
            }
        pose.position = pose.target + distance * back;
        return pose;
    }
    const glm::dvec3 back = default_view_direction();
    CameraPose pose = fit_box(lo, hi, back, s.camera_up, s.fov, aspect_, !s.target_given);
    if (s.target_given) {
        const double distance = glm::length(pose.position - pose.target);
        pose.target = s.camera_target;
        pose.position = pose.target + distance * back;
    }
    return pose;
}

FrameLayout layout_for(const RenderSettings& s, const OverlayRoom& room) {
    double aspect = scene_aspect(s);
    if (s.dimension == 3 && s.frame_to_domain) {
        const double margin = frame_margin(s.height);
        const double room_aspect = std::max(1.0, s.width - room.right - 2 * margin) /
                                   std::max(1.0, s.height - room.top - 2 * margin);
        if (s.scene_aspect > 0) {
            aspect = s.scene_aspect;
        } else if (s.camera_fixed || !s.camera_path.empty()) {
            // The camera is the user's: the rectangle follows the domain's
            // image from it, not from the default camera (whose width a
            // close or distant camera does not share: a dead band).
            std::vector<CameraPose> poses;
            if (s.camera_path.empty()) {
                poses.push_back(fixed_pose(s));
            } else {
                constexpr int samples = 64;
                const double t0 = s.camera_path.front().time, t1 = s.camera_path.back().time;
                for (int k = 0; k <= samples; ++k)
                    poses.push_back(
                        path_pose(s.camera_path, t0 + (t1 - t0) * k / samples, s.dimension));
            }
            aspect = 0;
            for (const CameraPose& pose : poses) {
                const double a = width_aspect(s.domain_min, s.domain_max, pose, room_aspect);
                if (a == 0) {
                    aspect = 0; // the room whole: some frame is a close-up
                    break;
                }
                aspect = std::max(aspect, a);
            }
        } else {
            const CameraPose pose = fit_box(s.domain_min, s.domain_max, default_view_direction(),
                                            glm::dvec3(0, 1, 0), 40, room_aspect);
            aspect = image_aspect(s.domain_min, s.domain_max, pose);
        }
    }
    return layout_frame(s.width, s.height, room, aspect);
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
        // A pose's region of the plane, else the domain.
        const glm::dvec3 size = s.domain_max - s.domain_min;
        double half_h = 0, half_w = 0;
        glm::dvec3 centre = pose.target - origin;
        if (pose.height > 0) {
            half_h = 0.5 * pose.height;
            half_w = half_h * r.width / r.height;
        } else {
            const double scale = std::min(r.width / size.x, r.height / size.y); // px per m
            half_w = 0.5 * r.width / scale;
            half_h = 0.5 * r.height / scale;
            centre = 0.5 * (s.domain_min + s.domain_max) - origin;
        }
        const double depth = 10 + 4 * s.radius;
        camera.projection =
            into_rect * glm::mat4(glm::ortho(centre.x - half_w, centre.x + half_w,
                                             centre.y - half_h, centre.y + half_h, -depth, depth));
        return camera;
    }
    camera.view = glm::lookAt(glm::vec3(pose.position - origin), glm::vec3(pose.target - origin),
                              glm::vec3(pose.up));
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
