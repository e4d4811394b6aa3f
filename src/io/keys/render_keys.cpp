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
        {.path = "shadows",
         .field = &S::shadows,
         .doc = "3D: the key light casts soft shadows (a shadow map filtered over about a "
                "particle's radius) on the fluid, the floor and the solids; 2D scenes have "
                "none. Off by default: it costs about as much as the spheres "
                "themselves on llvmpipe (docs/rendering.md)."},
        {.path = "ambient_occlusion",
         .field = &S::ambient_occlusion,
         .doc = "3D: screen-space ambient occlusion darkens creases, contact with the floor and "
                "walls, and the hollows of a splash, over about four particle radii; 2D scenes "
                "have none. Off by default: two passes over the image, as costly as the "
                "spheres on llvmpipe (docs/rendering.md)."},
        {.path = "floor",
         .field = &S::floor,
         .doc = "3D: a matte floor under the domain (against gravity; y without it) that "
                "receives the shadows and fades into the backdrop."},
        {.path = "tank",
         .field = &S::tank,
         .doc = "3D: the domain's walls drawn as faint glass (more opaque at grazing angles) "
                "besides its edges; false: the edges only."},
        {.path = "background",
         .field = &S::background,
         .doc = "The backdrop and overlay palette: light (a pale grey gradient, where every "
                "colour map's dark end stays visible) or dark (near-black, light text).",
         .choices = {"light", "dark"}},
        {.path = "backend",
         .field = &S::backend,
         .doc = "Headless GL context.",
         .choices = {"auto", "egl", "osmesa"}},
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
