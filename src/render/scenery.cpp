#include "render/scenery.hpp"

#include <cmath>
#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sph {

namespace {

void append_line(const glm::vec3& p, const glm::vec3& q, std::vector<OverlayVertex>& lines) {
    lines.push_back({p.x, p.y, p.z, -1});
    lines.push_back({q.x, q.y, q.z, -1});
}

// The edges of the box from lo to hi: in 2D (flat) its outline at depth 0,
// in 3D its twelve edges.
void append_edges(const glm::vec3& lo, const glm::vec3& hi, bool flat,
                  std::vector<OverlayVertex>& lines) {
    if (flat) {
        const glm::vec3 c[4] = {{lo.x, lo.y, 0}, {hi.x, lo.y, 0}, {hi.x, hi.y, 0}, {lo.x, hi.y, 0}};
        for (int k = 0; k < 4; ++k)
            append_line(c[k], c[(k + 1) % 4], lines);
        return;
    }
    for (int a = 0; a < 3; ++a)
        for (int corner = 0; corner < 4; ++corner) {
            glm::vec3 p = lo;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            p[b] = corner & 1 ? hi[b] : lo[b];
            p[c] = corner & 2 ? hi[c] : lo[c];
            glm::vec3 q = p;
            q[a] = hi[a];
            append_line(p, q, lines);
        }
}

// A box from lo to hi: in 2D (flat) a filled rectangle at depth `behind` with
// its outline, in 3D its edges.
void append_box(const glm::vec3& lo, const glm::vec3& hi, bool flat, float behind,
                std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& fill) {
    append_edges(lo, hi, flat, lines);
    if (!flat)
        return;
    const glm::vec3 c[4] = {{lo.x, lo.y, 0}, {hi.x, lo.y, 0}, {hi.x, hi.y, 0}, {lo.x, hi.y, 0}};
    for (int k : {0, 1, 2, 0, 2, 3})
        fill.push_back({c[k].x, c[k].y, behind, -1});
}

// The paddles at time t, relative to `origin`, as boxes (append_box).
void append_paddles(const std::vector<Paddle<3>>& paddles, bool flat, double t,
                    const glm::dvec3& origin, float behind, std::vector<OverlayVertex>& lines,
                    std::vector<OverlayVertex>& fill) {
    for (const Paddle<3>& paddle : paddles) {
        const Box<3> box = paddle.box_at(t);
        const glm::vec3 lo(box.min - origin), hi(box.max - origin);
        append_box({lo.x, lo.y, flat ? 0.f : lo.z}, {hi.x, hi.y, flat ? 0.f : hi.z}, flat, behind,
                   lines, fill);
    }
}

// The obstacles, positions relative to `origin`: in 2D each a filled shape at
// depth `behind` (behind the particles) with its outline; in 3D the edges of
// a box and three great circles of a sphere (a mesh is drawn solid, by
// mesh_obstacle_triangles).
void append_obstacles(const std::vector<SceneObstacle>& obstacles, bool flat,
                      const glm::dvec3& origin, float behind, std::vector<OverlayVertex>& lines,
                      std::vector<OverlayVertex>& fill) {
    constexpr int segments = 64;
    auto at = [&](const Vec3& p) {
        return glm::vec3(float(p[0] - origin.x), float(p[1] - origin.y),
                         flat ? 0.f : float(p[2] - origin.z));
    };
    auto triangle = [&](glm::vec3 p, glm::vec3 q, glm::vec3 r) {
        for (const glm::vec3& v : {p, q, r})
            fill.push_back({v.x, v.y, behind, -1});
    };
    for (const SceneObstacle& o : obstacles) {
        if (o.shape == ObstacleShape::mesh)
            continue;
        if (o.shape == ObstacleShape::box) {
            append_box(at(o.min), at(o.max), flat, behind, lines, fill);
            continue;
        }
        const glm::vec3 centre = at(o.centre);
        const float radius = float(o.radius);
        // 2D: the circle in the plane; 3D: one circle in each coordinate plane.
        for (int plane = 0; plane < (flat ? 1 : 3); ++plane) {
            const int a = plane, b = (plane + 1) % 3;
            auto point = [&](int k) {
                const float angle = 2.f * float(M_PI) * float(k) / float(segments);
                glm::vec3 p = centre;
                p[a] += radius * std::cos(angle);
                p[b] += radius * std::sin(angle);
                return p;
            };
            for (int k = 0; k < segments; ++k) {
                append_line(point(k), point(k + 1), lines);
                if (flat)
                    triangle(centre, point(k), point(k + 1));
            }
        }
    }
}

// The mesh obstacles' triangles relative to `origin`, each vertex followed by
// its face's normal (x, y, z, nx, ny, nz): flat shading shows the facets the
// simulation sees.
std::vector<float> mesh_obstacle_triangles(const std::vector<SceneObstacle>& obstacles,
                                           const glm::dvec3& origin) {
    std::vector<float> out;
    for (const SceneObstacle& o : obstacles) {
        if (o.shape != ObstacleShape::mesh || !o.mesh)
            continue;
        const TriangleMesh& mesh = *o.mesh;
        for (std::size_t t = 0; t < mesh.triangles().size(); ++t)
            for (const std::uint32_t v : mesh.triangles()[t]) {
                for (int a = 0; a < 3; ++a)
                    out.push_back(float(mesh.vertices()[v][a] - origin[a]));
                for (int a = 0; a < 3; ++a)
                    out.push_back(float(mesh.face_normals()[t][a]));
            }
    }
    return out;
}

} // namespace

Scenery::Scenery(const RenderSettings& s)
    : dimension_(s.dimension), domain_min_(s.domain_min), domain_max_(s.domain_max),
      behind_(float(-2 * s.radius)), obstacles_(s.obstacles), paddles_(s.paddles) {
    const std::vector<float> solid =
        mesh_obstacle_triangles(obstacles_, 0.5 * (s.domain_min + s.domain_max));
    if (solid.empty())
        return;
    solid_program_ = gl::link_program(shaders::solid_vert, shaders::solid_frag, shaders::lighting);
    solid_vao_ = gl::VertexArray::generate();
    glBindVertexArray(solid_vao_.id());
    solid_buffer_ = gl::Buffer::generate();
    glBindBuffer(GL_ARRAY_BUFFER, solid_buffer_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(solid.size() * sizeof(float)), solid.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
    solid_vertex_count_ = GLsizei(solid.size() / 6);
    glBindVertexArray(0);
}

void Scenery::draw(const FlatPainter& painter, const Camera& camera, double time) {
    const bool flat = dimension_ == 2;
    const glm::mat4 clip = camera.projection * camera.view;
    // Mesh obstacles, solid and lit like the particles, depth-tested with them.
    if (solid_vertex_count_ > 0 && !camera.orthographic) {
        const GLuint program = solid_program_.id();
        glUseProgram(program);
        glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                           glm::value_ptr(camera.view));
        glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                           glm::value_ptr(camera.projection));
        glUniform3f(glGetUniformLocation(program, "u_colour"), 0.62f, 0.6f, 0.56f);
        glBindVertexArray(solid_vao_.id());
        glDrawArrays(GL_TRIANGLES, 0, solid_vertex_count_);
    }

    // The domain box, depth-tested so the fluid hides its far edges, and the
    // other obstacles.
    lines_.clear();
    fill_.clear();
    append_edges(glm::vec3(domain_min_ - camera.origin), glm::vec3(domain_max_ - camera.origin),
                 camera.orthographic, lines_);
    append_obstacles(obstacles_, flat, camera.origin, behind_, lines_, fill_);
    painter.draw(fill_, GL_TRIANGLES, clip, {0.3f, 0.32f, 0.36f, 1.f});
    painter.draw(lines_, GL_LINES, clip, {0.55f, 0.58f, 0.62f, 1.f});
    // Paddles in a warmer grey than the static solids: the parts that move.
    if (!paddles_.empty()) {
        lines_.clear();
        fill_.clear();
        append_paddles(paddles_, flat, time, camera.origin, behind_, lines_, fill_);
        painter.draw(fill_, GL_TRIANGLES, clip, {0.45f, 0.38f, 0.3f, 1.f});
        painter.draw(lines_, GL_LINES, clip, {0.78f, 0.66f, 0.5f, 1.f});
    }
}

} // namespace sph
