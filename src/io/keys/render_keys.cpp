// The render object's keys: the scene's side of the renderer's settings
// (render/frame_renderer.hpp turns them into its own).
#include "io/keys/scene_keys.hpp"

namespace sph {

const KeyTable<Scene::Render>& render_keys() {
    using S = Scene::Render;
    static const KeyTable<S> keys{
        {.path = "size",
         .field = &S::size,
         .unit = "px",
         .doc = "Image width and height.",
         .min = 1,
         .max = 16384},
        {.path = "colour",
         .field = &S::colour,
         .doc = "Field the particles are coloured by.",
         .choices = {"velocity", "density", "pressure"}},
        {.path = "colour_map",
         .field = &S::colour_map,
         .doc = "Colour map; auto: viridis for speed, diverging around rho0 for density, turbo "
                "for pressure.",
         .choices = {"auto", "viridis", "turbo", "diverging"}},
        {.path = "range",
         .field = &S::range,
         .unit = "field unit",
         .doc = "Field values at the two ends of the colour map, used as given for any field; by "
                "default each field's own from the scene's physics: speed 0..v = sqrt(v0^2 + 2 "
                "|g| H) (H: the highest fluid or inlet above the floor, v0 its speed), pressure "
                "0..rho0 v^2 / 2, density rho0 (1 +- max(1%, 2 v^2 / c^2)). A frame with over 5% "
                "of its particles outside warns.",
         .absent = "from the scene"},
        {.path = "spheres",
         .field = &S::spheres,
         .doc = "How spheres are drawn: ray-cast impostors (fast) or the seed's instanced "
                "meshes.",
         .choices = {"impostor", "mesh"}},
        {.path = "style",
         .field = &S::style,
         .doc = "How the fluid is drawn: spheres, one per particle; surface, the free surface "
                "reconstructed each frame from the particles (3D: an OpenVDB level set meshed "
                "and shaded as water; 2D: the filled region with its outline) and coloured by "
                "the colour field at its vertices (render.surface.*).",
         .choices = {"spheres", "surface"}},
        {.path = "cull_buried",
         .field = &S::cull_buried,
         .doc = "3D: skip particles buried under two full layers of fluid (a camera outside the "
                "fluid cannot see them); false draws every particle."},
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
         .doc = "Font file (TrueType/OpenType) for the overlay's text; a file that cannot be "
                "read warns and the default is used.",
         .absent = "DejaVu Sans (fonts-dejavu-core), else fc-match's, else a bitmap font"},
        {.path = "backend",
         .field = &S::backend,
         .doc = "Headless GL context.",
         .choices = {"auto", "egl", "osmesa"}},
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
    static const KeyTable<S> keys{
        {.path = "position",
         .field = &S::position,
         .unit = "m",
         .doc = "Camera position (3D scenes).",
         .absent = "frames the domain",
         .size = VectorSize::three},
        {.path = "target",
         .field = &S::target,
         .unit = "m",
         .doc = "Point the camera looks at (3D scenes).",
         .absent = "domain centre",
         .size = VectorSize::three},
        {.path = "fov",
         .field = &S::fov,
         .unit = "degrees",
         .doc = "Vertical field of view (3D scenes).",
         .bound = Bound::positive},
    };
    return keys;
}

} // namespace sph
