#pragma once
// The render section's choices as enums. A scene's strings become these where
// they are read (scene/keys/render_keys.cpp), so nothing compares the strings
// later. Each enum's names, in the order of its values, are its key's choices
// and how run.json, `sphclip keys` and messages spell it.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

// What the particles are coloured by (render.colour).
enum class ColourField { velocity, density, pressure };
// render.colour_map; a scene's "auto" is none, the field's own map.
enum class ColourMap { viridis, turbo, diverging };
// How spheres are drawn (render.spheres).
enum class SphereDrawing { impostor, mesh };
// How the fluid is drawn (render.style).
enum class FluidStyle { spheres, surface };
// The backdrop and overlay palette (render.background).
enum class Background { light, dark };
// The headless GL context (render.backend, --backend); a scene's "auto" is
// none: EGL, then OSMesa.
enum class GlBackend { egl, osmesa };
// What the default camera frames (render.camera.fit).
enum class CameraFit { domain, fluid, follow };
// Over MPI ranks, how a frame's spheres reach rank 0 (render.mpi_composite;
// a scene's "auto" is none: by particle count): rank 0 draws them all, or
// each rank draws its own and rank 0 composites by depth.
enum class MpiComposite { gather, depth };

// Each enum's names, in the order of its values.
template <class E>
const std::vector<std::string>& choice_names();

#define SPH_CHOICE_NAMES(E, ...)                                                                   \
    template <>                                                                                    \
    inline const std::vector<std::string>& choice_names<E>() {                                     \
        static const std::vector<std::string> names{__VA_ARGS__};                                  \
        return names;                                                                              \
    }
SPH_CHOICE_NAMES(ColourField, "velocity", "density", "pressure")
SPH_CHOICE_NAMES(ColourMap, "viridis", "turbo", "diverging")
SPH_CHOICE_NAMES(SphereDrawing, "impostor", "mesh")
SPH_CHOICE_NAMES(FluidStyle, "spheres", "surface")
SPH_CHOICE_NAMES(Background, "light", "dark")
SPH_CHOICE_NAMES(GlBackend, "egl", "osmesa")
SPH_CHOICE_NAMES(CameraFit, "domain", "fluid", "follow")
SPH_CHOICE_NAMES(MpiComposite, "gather", "depth")
#undef SPH_CHOICE_NAMES

template <class E>
const std::string& choice_name(E value) {
    return choice_names<E>()[static_cast<std::size_t>(value)];
}

// The choices of a key whose absence of a value is spelled "auto"
// (auto_enum_field): "auto", then the enum's names.
template <class E>
std::vector<std::string> auto_choice_names() {
    std::vector<std::string> names{"auto"};
    names.insert(names.end(), choice_names<E>().begin(), choice_names<E>().end());
    return names;
}

// The value spelled `name`; none for a name the enum does not have. For the
// program's edges other than the scene (command-line flags, benchmark lists).
template <class E>
std::optional<E> choice_named(std::string_view name) {
    const auto& names = choice_names<E>();
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end())
        return std::nullopt;
    return static_cast<E>(at - names.begin());
}

} // namespace sph
