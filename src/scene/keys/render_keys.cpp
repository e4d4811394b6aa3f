// The render object's keys: the scene's side of the renderer's settings
// (render/frame_renderer.hpp turns them into its own).
#include "scene/key_walk.hpp"
#include "scene/keys/scene_keys.hpp"

#include <cmath>

namespace sph {

const KeyTable<Scene::Render>& render_keys() {
    using S = Scene::Render;
    const std::string flat_refused =
        "is a 3D key: a 2D scene is drawn flat, with no light, floor, tank or hidden "
        "particles; leave it out";
    static const KeyTable<S> keys{
        {.path = "size",
         .field = &S::size,
         .unit = "px",
         .doc = "Image width and height.",
         .min = 1,
         .max = 16384},
        {.path = "colour",
         .field = enum_field<&S::colour>(),
         .doc = "Field the particles are coloured by.",
         .choices = choice_names<ColourField>()},
        {.path = "colour_map",
         .field = auto_enum_field<&S::colour_map>(),
         .doc = "Colour map; auto: viridis for speed, diverging around rho0 for density, turbo "
                "for pressure.",
         .choices = auto_choice_names<ColourMap>()},
        {.path = "range",
         .field = &S::range,
         .unit = "field unit",
         .doc = "Field values at the two ends of the colour map, used as given for any field; by "
                "default each field's own from the scene's physics: speed 0..the fastest source's "
                "sqrt(v0^2 + 4 |g| H) for a block with room to collapse (a dam break's front, "
                "Ritter's 2 sqrt(g H)), sqrt(v0^2 + 2 |g| H) for an emitter or a pool filling "
                "the floor (a fall; H: the source's top above the floor, v0 its speed); pressure "
                "0..rho0 v^2 / 2 and density rho0 (1 +- max(1%, 2 v^2 / c^2)) with v the fall's "
                "speed. A frame with over 5% of its particles outside warns.",
         .absent = "from the scene"},
        {.path = "spheres",
         .field = enum_field<&S::spheres>(),
         .doc = "How spheres are drawn: ray-cast impostors (fast) or the seed's instanced "
                "meshes.",
         .choices = choice_names<SphereDrawing>()},
        {.path = "style",
         .field = enum_field<&S::style>(),
         .doc = "How the fluid is drawn: spheres, one per particle; surface, the free surface "
                "reconstructed each frame from the particles (3D: an OpenVDB level set meshed "
                "and shaded as water; 2D: the filled region with its outline) and coloured by "
                "the colour field at its vertices (render.surface.*).",
         .choices = choice_names<FluidStyle>()},
        {.path = "mpi_composite",
         .field = auto_enum_field<&S::mpi_composite>(),
         .doc = "Under mpirun: gather, rank 0 draws every particle (each rank holds the whole "
                "state); depth, each rank draws the spheres it owns and rank 0 composites them "
                "by depth, then draws shadows' receivers, ambient occlusion and overlay once: "
                "the same pixels. auto: gather (measured on 2 ranks of a 2-core machine, depth "
                "won where most particles are drawn, a gas from 100k, and for a 1M fluid at "
                "640x360, and lost for a fluid at 1280x720 up to 1M; a particle count cannot "
                "tell them apart; docs/mpi.md, \"Rendering over ranks\"). depth "
                "needs render.style spheres with impostors and width x 4 samples within the "
                "GL's texture size.",
         .choices = auto_choice_names<MpiComposite>()},
        {.path = "cull_buried",
         .field = &S::cull_buried,
         .doc = "3D only (a 2D scene refuses it): skip particles buried under two full layers "
                "of fluid (a camera outside the fluid cannot see them); false draws every "
                "particle.",
         .refused = flat_refused,
         .only_dimension = 3},
        {.path = "video_quality",
         .field = &S::video_quality,
         .doc = "MP4 constant quality (x264 CRF): 0 lossless, 18-23 visually good, 51 worst.",
         .min = 0,
         .max = 51},
        {.path = "video_preset",
         .field = enum_field<&S::video_preset>(),
         .doc = "MP4 encoder speed: faster presets make larger files at the same quality.",
         .choices = video_preset_names()},
        {.path = "title",
         .field = &S::title,
         .doc = "A title line above the scene, on the left.",
         .absent = "none"},
        {.path = "caption",
         .field = &S::caption,
         .doc = "The line above the scene (on the right, beside a title): {time} (s, 3 "
                "decimals), {frame} and {steps} are replaced; empty: none.",
         .absent = "t = {time} s    frame {frame}"},
        {.path = "font",
         .field = &S::font,
         .doc = "Font file (TrueType/OpenType) for the overlay's text; a file that is not a "
                "regular file of at most 64 MiB that FreeType reads is refused.",
         .absent = "DejaVu Sans (fonts-dejavu-core), else fc-match's, else a bitmap font"},
        {.path = "shadows",
         .field = &S::shadows,
         .doc = "3D only (a 2D scene refuses it): the key light casts soft shadows (a shadow "
                "map filtered over about a particle's radius) on the fluid, the floor and the "
                "solids. Off by default: it costs about as much as the spheres themselves on "
                "llvmpipe (docs/rendering.md).",
         .refused = flat_refused,
         .only_dimension = 3},
        {.path = "ambient_occlusion",
         .field = &S::ambient_occlusion,
         .doc = "3D only (a 2D scene refuses it): screen-space ambient occlusion darkens "
                "creases, contact with the floor and walls, and the hollows of a splash, over "
                "about four particle radii. Off by default: two passes over the image, as "
                "costly as the spheres on llvmpipe (docs/rendering.md).",
         .refused = flat_refused,
         .only_dimension = 3},
        {.path = "floor",
         .field = &S::floor,
         .doc = "3D only (a 2D scene refuses it): a matte floor under the domain (against "
                "gravity; y without it) that receives the shadows and fades into the backdrop.",
         .refused = flat_refused,
         .only_dimension = 3},
        {.path = "tank",
         .field = &S::tank,
         .doc = "3D only (a 2D scene refuses it): the domain's walls drawn as faint glass (more "
                "opaque at grazing angles) besides its edges; false: the edges only.",
         .refused = flat_refused,
         .only_dimension = 3},
        {.path = "background",
         .field = enum_field<&S::background>(),
         .doc = "The backdrop and overlay palette: light (a pale grey gradient, where every "
                "colour map's dark end stays visible) or dark (near-black, light text).",
         .choices = choice_names<Background>()},
        {.path = "backend",
         .field = auto_enum_field<&S::backend>(),
         .doc = "Headless GL context.",
         .choices = auto_choice_names<GlBackend>()},
    };
    return keys;
}

const KeyTable<Scene::Render::Surface>& surface_keys() {
    using S = Scene::Render::Surface;
    static const KeyTable<S> keys{
        {.path = "voxel",
         .field = &S::voxel,
         .unit = "x spacing",
         .doc = "render.style = surface: the level set's voxel (2D: the grid's cell), 0.1 to 2 "
                "particle spacings; smaller is finer and slower (cost ~ 1 / voxel^3 in 3D).",
         .bound = Bound::positive},
        {.path = "radius",
         .field = &S::radius,
         .unit = "x spacing",
         .doc = "render.style = surface: 3D, the radius of the sphere each particle adds to the "
                "level set before it is smoothed and eroded back by radius - 0.5 (closes gaps "
                "between particles), at least 1.5 voxels; 2D, half the support of the kernel "
                "summed on the grid. 0.5 to 4 particle spacings.",
         .bound = Bound::positive},
        {.path = "smoothing",
         .field = &S::smoothing,
         .doc = "render.style = surface: smoothing passes, 3D Gaussian filter passes over the "
                "level set, 2D binomial blur passes over the grid; 0 none.",
         .min = 0,
         .max = 20},
    };
    return keys;
}

const KeyTable<Scene::Render::Camera>& camera_keys() {
    using S = Scene::Render::Camera;
    const std::string three_d = "is a 3D camera key: a 2D scene is seen straight on; "
                                "render.camera.centre and render.camera.height set its view";
    const std::string two_d = "is a 2D camera key: a 3D scene's camera is set by "
                              "render.camera.position, target, up and fov";
    static const KeyTable<S> keys{
        {.path = "fit",
         .field = enum_field<&S::fit>(),
         .doc = "What the default camera frames: domain (the tank, fixed), fluid (where the "
                "fluid starts: its blocks and emitters, fixed) or follow (the fluid's bounds "
                "over time, smoothed: it widens at once to keep every particle in view and "
                "narrows with a 0.5 s time constant). 2D: the region of the plane in view; 3D: "
                "the distance and target at which the box fills the frame at `fov`.",
         .choices = choice_names<CameraFit>()},
        {.path = "position",
         .field = &S::position,
         .unit = "m",
         .doc = "Camera position (3D scenes only).",
         .absent = "from fit: front right, 20 degrees above",
         .size = VectorSize::three,
         .refused = three_d,
         .only_dimension = 3},
        {.path = "target",
         .field = &S::target,
         .unit = "m",
         .doc = "Point the camera looks at (3D scenes only).",
         .absent = "from fit: the framed box's centre",
         .size = VectorSize::three,
         .refused = three_d,
         .only_dimension = 3},
        {.path = "up",
         .field = &S::up,
         .doc = "The direction that is up in the image (3D scenes only); must not be along the "
                "view.",
         .absent = "[0, 1, 0]",
         .size = VectorSize::three,
         .refused = three_d,
         .only_dimension = 3},
        {.path = "fov",
         .field = &S::fov,
         .unit = "degrees",
         .doc = "Vertical field of view (3D scenes only), below 180.",
         .bound = Bound::positive,
         .refused = three_d,
         .only_dimension = 3},
        {.path = "centre",
         .field = &S::centre,
         .unit = "m",
         .doc = "The centre of the plane's region in view (2D scenes only).",
         .absent = "from fit",
         .size = VectorSize::two,
         .refused = two_d,
         .only_dimension = 2},
        {.path = "height",
         .field = &S::height,
         .unit = "m",
         .doc = "The height of the plane's region in view (2D scenes only); its width follows "
                "from the frame's aspect.",
         .bound = Bound::positive,
         .absent = "from fit",
         .refused = two_d,
         .only_dimension = 2},
        {.path = "aspect",
         .field = &S::aspect,
         .doc = "The width / height of the scene's rectangle, beside the overlay's bands (3D "
                "scenes only); by default as wide as the domain's image from a fixed camera "
                "or path (the widest over the clip), the room whole where the domain fills the "
                "view, else the domain's image from the default camera. run.json records it "
                "with each camera, so a pasted camera draws its frame again.",
         .bound = Bound::positive,
         .absent = "from the camera",
         .refused = three_d,
         .only_dimension = 3},
    };
    return keys;
}

const KeyList<Scene::Render::Camera::Keyframe>& camera_path_keys() {
    using S = Scene::Render::Camera::Keyframe;
    static const KeyList<S> list{
        .path = "render.camera.path",
        .doc = "Camera keyframes, in increasing time; between them the camera moves on a cubic "
               "Hermite curve with Catmull-Rom tangents (position, target, up; fov and height "
               "in log), before the first and after the last it holds still.",
        .keys = {{.path = "time",
                  .field = &S::time,
                  .unit = "s",
                  .doc = "When the camera is at this keyframe.",
                  .bound = Bound::non_negative,
                  .absent = "required",
                  .required = true},
                 {.path = "position",
                  .field = &S::position,
                  .unit = "m",
                  .doc = "Camera position (3D; required there).",
                  .absent = "required in 3D",
                  .size = VectorSize::three},
                 {.path = "target",
                  .field = &S::target,
                  .unit = "m",
                  .doc = "Point looked at (3D; required there).",
                  .absent = "required in 3D",
                  .size = VectorSize::three},
                 {.path = "up",
                  .field = &S::up,
                  .doc = "Up in the image (3D).",
                  .absent = "[0, 1, 0]",
                  .size = VectorSize::three},
                 {.path = "fov",
                  .field = &S::fov,
                  .unit = "degrees",
                  .doc = "Vertical field of view (3D), below 180.",
                  .bound = Bound::positive,
                  .absent = "render.camera.fov"},
                 {.path = "centre",
                  .field = &S::centre,
                  .unit = "m",
                  .doc = "Centre of the view (2D; required there).",
                  .absent = "required in 2D",
                  .size = VectorSize::two},
                 {.path = "height",
                  .field = &S::height,
                  .unit = "m",
                  .doc = "Height of the view (2D; required there).",
                  .bound = Bound::positive,
                  .absent = "required in 2D"}},
        .check = [](const S& k, int dimension) -> std::optional<KeyProblem> {
            if (dimension == 2) {
                const char* three_d = k.position ? "position"
                                      : k.target ? "target"
                                      : k.up     ? "up"
                                      : k.fov    ? "fov"
                                                 : nullptr;
                if (three_d)
                    return KeyProblem{three_d,
                                      "is a 3D key; a 2D keyframe gives centre and height"};
                if (!k.centre)
                    return KeyProblem{"centre", "a 2D keyframe needs centre and height"};
                if (!k.height)
                    return KeyProblem{"height", "a 2D keyframe needs centre and height"};
                return std::nullopt;
            }
            if (k.centre || k.height)
                return KeyProblem{k.centre ? "centre" : "height",
                                  "is a 2D key; a 3D keyframe gives position and target"};
            if (!k.position)
                return KeyProblem{"position", "a 3D keyframe needs position and target"};
            if (!k.target)
                return KeyProblem{"target", "a 3D keyframe needs position and target"};
            if (*k.position == *k.target)
                return KeyProblem{"position", "equals the keyframe's target: the camera needs a "
                                              "direction to look along"};
            if (k.fov && *k.fov >= 180)
                return KeyProblem{"fov", fmt::format("must be below 180 degrees, got {}", *k.fov)};
            return std::nullopt;
        }};
    return list;
}

const KeyTable<Scene::Render::Camera::Orbit>& orbit_keys() {
    using S = Scene::Render::Camera::Orbit;
    static const KeyTable<S> keys{
        {.path = "turns",
         .field = &S::turns,
         .doc = "Turns round the fit's target over the clip (3D); negative: clockwise seen from "
                "above."},
        {.path = "elevation_deg",
         .field = &S::elevation_deg,
         .unit = "degrees",
         .doc = "The camera's height above the target's horizontal plane, as an angle, -89 to "
                "89."},
        {.path = "start_deg",
         .field = &S::start_deg,
         .unit = "degrees",
         .doc = "The camera's azimuth at t = 0, from +z towards +x."},
        {.path = "distance",
         .field = &S::distance,
         .unit = "m",
         .doc = "From the target; by default the least at which the fit's box fills the frame "
                "from every azimuth, the same all round.",
         .bound = Bound::positive,
         .absent = "from fit"},
    };
    return keys;
}

namespace {

// The orbit, an object rather than a key of camera_keys() (whose keys of
// one dimension refuse themselves, Key::only_dimension), is 3D only.
void refuse_for_dimension(const FieldReader& r, int dimension) {
    if (dimension == 2 && r.present("render.camera.orbit"))
        r.fail("render.camera.orbit",
               "is a 3D camera key: a 2D scene is seen straight on; render.camera.centre and "
               "render.camera.height set its view");
}

} // namespace

void read_camera(FieldReader& r, Scene& s) {
    using C = Scene::Render::Camera;
    const int dim = s.dimension;
    const C d;
    refuse_for_dimension(r, dim);
    read_keys(r, "render.camera", camera_keys(), d, s.render.camera, dim);
    C& c = s.render.camera;
    c.path = read_list(r, camera_path_keys(), dim);
    for (std::size_t i = 1; i < c.path.size(); ++i)
        if (!(c.path[i].time > c.path[i - 1].time))
            r.fail(fmt::format("render.camera.path[{}].time", i),
                   fmt::format("keyframe times must increase: {} s follows {} s", c.path[i].time,
                               c.path[i - 1].time));
    // The orbit's keys are read (and recorded) whether or not it is given.
    const C::Orbit orbit = read_keys(r, "render.camera.orbit", orbit_keys(), C::Orbit{}, dim);
    if (r.present("render.camera.orbit")) {
        if (!r.find("render.camera.orbit")->is_object())
            r.fail("render.camera.orbit",
                   "expected an object, got " + describe(*r.find("render.camera.orbit")));
        if (!(std::abs(orbit.elevation_deg) <= 89))
            r.fail("render.camera.orbit.elevation_deg",
                   fmt::format("must be between -89 and 89 degrees, got {}", orbit.elevation_deg));
        c.orbit = orbit;
    }
    // One way of moving the camera at a time.
    const bool fixed = c.position || c.target || c.centre || c.height;
    if (!c.path.empty() && (c.orbit || fixed))
        r.fail("render.camera.path",
               c.orbit ? "given with render.camera.orbit: the camera follows one of them"
                       : "given with a fixed camera (position, target, centre or height): the "
                         "path's keyframes set the camera");
    if (c.orbit && c.position)
        r.fail("render.camera.orbit", "given with render.camera.position: the orbit sets "
                                      "the position (its target may be given)");
    if (c.fov >= 180)
        r.fail("render.camera.fov", fmt::format("must be below 180 degrees, got {}", c.fov));
    if (c.up && (*c.up)[0] == 0 && (*c.up)[1] == 0 && (*c.up)[2] == 0)
        r.fail("render.camera.up", "must not be zero");
    if (dim == 3 && c.position) {
        // The target defaults to the domain's centre.
        Vec3 target = c.target.value_or(Vec3{});
        if (!c.target)
            for (int a = 0; a < 3; ++a)
                target[a] = 0.5 * (s.domain.min[a] + s.domain.max[a]);
        if (*c.position == target)
            r.fail("render.camera.position",
                   fmt::format("equals the camera's target {}: the camera needs a direction to "
                               "look along",
                               format_vector(target, 3)));
        const Vec3 up = c.up.value_or(Vec3{0, 1, 0});
        const Vec3 view{target[0] - (*c.position)[0], target[1] - (*c.position)[1],
                        target[2] - (*c.position)[2]};
        const Vec3 cross{view[1] * up[2] - view[2] * up[1], view[2] * up[0] - view[0] * up[2],
                         view[0] * up[1] - view[1] * up[0]};
        const double v2 = view[0] * view[0] + view[1] * view[1] + view[2] * view[2];
        const double u2 = up[0] * up[0] + up[1] * up[1] + up[2] * up[2];
        const double c2 = cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2];
        if (c2 <= 1e-12 * v2 * u2)
            r.fail(c.up ? "render.camera.up" : "render.camera.position",
                   "the view is along the up direction: give render.camera.up across it");
    }
}

json write_camera(const Scene::Render::Camera& c, int dimension) {
    // Only the keys of the scene's dimension (Key::only_dimension): run.json's
    // scene reads back.
    json out = write_keys(camera_keys(), c, dimension);
    if (!c.path.empty())
        out["path"] = write_list(camera_path_keys(), c.path, dimension);
    if (c.orbit)
        out["orbit"] = write_keys(orbit_keys(), *c.orbit, dimension);
    return out;
}

} // namespace sph
