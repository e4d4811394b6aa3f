#pragma once
// The scene's solids around the fluid: mesh obstacles, solid and lit as the
// particles are (3D); the domain box; the other obstacles, filled with their
// outline (2D) or as edges (3D); and the paddles where their motion has them
// at the frame's time. Depth-tested with the particles.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/overlay.hpp"
#include "render/render_settings.hpp"

#include <vector>

namespace sph {

class Scenery {
  public:
    // Uploads the mesh obstacles, which never move.
    explicit Scenery(const RenderSettings& settings);
    void draw(const FlatPainter& painter, const Camera& camera, double time);

  private:
    int dimension_;
    glm::dvec3 domain_min_, domain_max_;
    float behind_; // 2D: the fills' depth, behind the particles
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
