#pragma once
// The scene's solids around the fluid: mesh obstacles, solid and lit as the
// particles are (3D); the domain box, its walls as faint glass (3D,
// render.tank); the other obstacles, filled with their outline (2D) or as
// edges (3D); the paddles where their motion has them at the frame's time;
// and the floor under it all (3D, render.floor). Depth-tested with the
// particles.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/lighting.hpp"
#include "render/overlay.hpp"
#include "render/palette.hpp"
#include "render/render_settings.hpp"

#include <vector>

namespace sph {

class Scenery {
  public:
    // Uploads the mesh obstacles, which never move.
    explicit Scenery(const RenderSettings& settings);
    // The floor (before the particles: it is opaque where they meet it and
    // fades into the backdrop away from the domain).
    void draw_floor(const Camera& camera) const;
    // The mesh obstacles' depth, through the shadow map's `light`.
    void draw_depth(const Camera& light) const;
    // The mesh obstacles, solid and lit like the particles (3D), before the
    // ambient occlusion so it sees them.
    void draw_solids(const Camera& camera) const;
    // The tank's walls as glass (3D, render.tank), after the particles and
    // the solids: it is blended over them.
    void draw_glass(const Camera& camera) const;
    // Everything else, after the glass: the domain box's edges, the other
    // obstacles and the paddles.
    void draw(const FlatPainter& painter, const Camera& camera, double time);
    // The light the solids and the floor are lit with; by default as in 2D.
    void set_lighting(const Lighting& lighting) { lighting_ = lighting; }
    // The radius of the sphere around the domain's centre that holds the
    // domain and what the shadows need of the floor, m.
    double reach() const { return reach_; }

  private:
    int dimension_;
    glm::dvec3 domain_min_, domain_max_;
    float behind_;     // 2D: the fills' depth, behind the particles
    int image_height_; // px
    const Palette& palette_;
    Lighting lighting_;
    double reach_;
    glm::vec3 floor_up_; // scene coordinates
    glm::vec2 floor_fade_;
    gl::Program floor_program_, glass_program_;
    gl::VertexArray floor_vao_, glass_vao_;
    gl::Buffer floor_buffer_, glass_buffer_;
    GLsizei glass_vertex_count_ = 0;
    std::vector<SceneObstacle> obstacles_;
    std::vector<Paddle<3>> paddles_;
    gl::Program solid_program_;
    gl::VertexArray solid_vao_;
    gl::Buffer solid_buffer_;
    GLsizei solid_vertex_count_ = 0;
    // Scratch reused from frame to frame.
    std::vector<OverlayVertex> lines_, fill_;
};

} // namespace sph
