#include "render/scenery.hpp"

#include <algorithm>
#include <cmath>
#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

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

// A vertex array of (x, y, z, nx, ny, nz) vertices from `data`, as the solid
// vertex shader reads them.
void upload_with_normals(const gl::VertexArray& vao, const gl::Buffer& buffer,
                         const std::vector<float>& data) {
    glBindVertexArray(vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
    glBindVertexArray(0);
}

// The box of half extents `e` around the origin, as triangles with their
// outward normals, but for the face on the floor (along -up): the tank's
// glass stands on the floor.
std::vector<float> glass_faces(const glm::vec3& e, int up_axis, float up_sign) {
    std::vector<float> out;
    for (int a = 0; a < 3; ++a)
        for (const float side : {-1.f, 1.f}) {
            if (a == up_axis && side == -up_sign)
                continue;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            glm::vec3 normal(0);
            normal[a] = side;
            auto corner = [&](float u, float v) {
                glm::vec3 p;
                p[a] = side * e[a];
                p[b] = u * e[b];
                p[c] = v * e[c];
                return p;
            };
            const glm::vec3 q[4] = {corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)};
            for (int k : {0, 1, 2, 0, 2, 3}) {
                out.insert(out.end(), {q[k].x, q[k].y, q[k].z});
                out.insert(out.end(), {normal.x, normal.y, normal.z});
            }
        }
    return out;
}

} // namespace

Scenery::Scenery(const RenderSettings& s)
    : dimension_(s.dimension), domain_min_(s.domain_min), domain_max_(s.domain_max),
      behind_(float(-2 * s.radius)), image_height_(s.height), palette_(palette(s.background)),
      obstacles_(s.obstacles), paddles_(s.paddles) {
    const std::string lighting = lighting_source(casts_shadows(s));
    const glm::vec3 half(0.5 * (s.domain_max - s.domain_min));
    reach_ = 1.02 * glm::length(glm::dvec3(half));
    if (dimension_ == 3 && (s.floor || s.tank)) {
        int up_axis = 1;
        for (int a = 0; a < 3; ++a)
            if (std::abs(s.up[a]) > 0.5)
                up_axis = a;
        const float up_sign = s.up[up_axis] < 0 ? -1.f : 1.f;
        floor_up_ = glm::vec3(0);
        floor_up_[up_axis] = up_sign;
        // The floor: fully there out to a little past the domain's
        // footprint, gone at three times that.
        const glm::vec3 across = half - glm::dot(half, floor_up_) * floor_up_;
        const float footprint = glm::length(across);
        floor_fade_ = {1.1f * footprint, 3.f * footprint};
        reach_ = std::max(reach_, 1.3 * double(footprint));
        // Where the key light reaches it, the floor is the backdrop itself:
        // only a shadow or the ambient occlusion (which reads its depth)
        // shows it. Without either it would paint the backdrop over itself
        // (8 ms of a 1280x720 frame on llvmpipe), so it is left out.
        if (s.floor && (casts_shadows(s) || s.ambient_occlusion)) {
            const int b = (up_axis + 1) % 3, c = (up_axis + 2) % 3;
            std::vector<float> quad;
            for (const auto& [u, v] :
                 {std::pair{-1.f, -1.f}, {1.f, -1.f}, {-1.f, 1.f}, {1.f, 1.f}}) {
                glm::vec3 p(0);
                p[up_axis] = -up_sign * half[up_axis];
                p[b] = u * floor_fade_.y;
                p[c] = v * floor_fade_.y;
                quad.insert(quad.end(), {p.x, p.y, p.z});
            }
            floor_program_ = gl::link_program(shaders::floor_vert, shaders::floor_frag, lighting);
            floor_vao_ = gl::VertexArray::generate();
            glBindVertexArray(floor_vao_.id());
            floor_buffer_ = gl::Buffer::generate();
            glBindBuffer(GL_ARRAY_BUFFER, floor_buffer_.id());
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(quad.size() * sizeof(float)), quad.data(),
                         GL_STATIC_DRAW);
            glEnableVertexAttribArray(0);
            glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
            glBindVertexArray(0);
        }
        if (s.tank) {
            const std::vector<float> faces = glass_faces(half, up_axis, up_sign);
            glass_program_ = gl::link_program(shaders::solid_vert, shaders::glass_frag, lighting);
            glass_vao_ = gl::VertexArray::generate();
            glass_buffer_ = gl::Buffer::generate();
            upload_with_normals(glass_vao_, glass_buffer_, faces);
            glass_vertex_count_ = GLsizei(faces.size() / 6);
        }
    }
    const std::vector<float> solid =
        mesh_obstacle_triangles(obstacles_, 0.5 * (s.domain_min + s.domain_max));
    if (solid.empty())
        return;
    solid_program_ = gl::link_program(shaders::solid_vert, shaders::solid_frag, lighting);
    solid_vao_ = gl::VertexArray::generate();
    solid_buffer_ = gl::Buffer::generate();
    upload_with_normals(solid_vao_, solid_buffer_, solid);
    solid_vertex_count_ = GLsizei(solid.size() / 6);
}

namespace {

void set_camera(GLuint program, const Camera& camera) {
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                       glm::value_ptr(camera.view));
    glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                       glm::value_ptr(camera.projection));
}

} // namespace

void Scenery::draw_floor(const Camera& camera) const {
    if (!floor_program_ || camera.orthographic)
        return;
    const GLuint program = floor_program_.id();
    set_camera(program, camera);
    sph::set_lighting(program, lighting_);
    glUniform3fv(glGetUniformLocation(program, "u_top"), 1, glm::value_ptr(palette_.backdrop_top));
    glUniform3fv(glGetUniformLocation(program, "u_bottom"), 1,
                 glm::value_ptr(palette_.backdrop_bottom));
    glUniform1f(glGetUniformLocation(program, "u_image_height"), float(image_height_));
    glUniform2fv(glGetUniformLocation(program, "u_fade"), 1, glm::value_ptr(floor_fade_));
    glUniform3fv(glGetUniformLocation(program, "u_floor_up"), 1, glm::value_ptr(floor_up_));
    glEnable(GL_BLEND);
    // Colour only: the frame stays opaque (a PNG with see-through edges
    // would show whatever a viewer puts behind it).
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    // A little behind its plane: the domain box's bottom edges and the
    // glass walls' feet lie on it, and without the offset the floor's depth
    // hid them in patches (z-fighting at its grazing angle).
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.f, 1.f);
    glBindVertexArray(floor_vao_.id());
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_BLEND);
}

void Scenery::draw_depth(const Camera& light) const {
    if (solid_vertex_count_ == 0)
        return;
    set_camera(solid_program_.id(), light);
    glBindVertexArray(solid_vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, solid_vertex_count_);
}

void Scenery::draw_solids(const Camera& camera) const {
    if (solid_vertex_count_ == 0 || camera.orthographic)
        return;
    const GLuint program = solid_program_.id();
    set_camera(program, camera);
    sph::set_lighting(program, lighting_);
    glUniform3fv(glGetUniformLocation(program, "u_colour"), 1, glm::value_ptr(palette_.solid));
    glBindVertexArray(solid_vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, solid_vertex_count_);
}

void Scenery::draw_glass(const Camera& camera) const {
    if (glass_vertex_count_ == 0 || camera.orthographic)
        return;
    const GLuint program = glass_program_.id();
    set_camera(program, camera);
    // A pale tint: reflections brighter than the backdrop, so the walls
    // read as glass, not as smoked panes.
    glUniform3f(glGetUniformLocation(program, "u_colour"), 0.97f, 0.98f, 1.f);
    // Over what is drawn, hiding nothing drawn later.
    glEnable(GL_BLEND);
    // Colour only: the frame stays opaque (a PNG with see-through edges
    // would show whatever a viewer puts behind it).
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glDepthMask(GL_FALSE);
    glBindVertexArray(glass_vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, glass_vertex_count_);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

void Scenery::draw(const FlatPainter& painter, const Camera& camera, double time) {
    const bool flat = dimension_ == 2;
    const glm::mat4 clip = camera.projection * camera.view;
    // The domain box, depth-tested so the fluid hides its far edges, and the
    // other obstacles.
    lines_.clear();
    fill_.clear();
    append_edges(glm::vec3(domain_min_ - camera.origin), glm::vec3(domain_max_ - camera.origin),
                 camera.orthographic, lines_);
    append_obstacles(obstacles_, flat, camera.origin, behind_, lines_, fill_);
    painter.draw(fill_, GL_TRIANGLES, clip, palette_.obstacle_fill);
    painter.draw(lines_, GL_LINES, clip, palette_.box_lines);
    // Paddles in a warmer grey than the static solids: the parts that move.
    if (!paddles_.empty()) {
        lines_.clear();
        fill_.clear();
        append_paddles(paddles_, flat, time, camera.origin, behind_, lines_, fill_);
        painter.draw(fill_, GL_TRIANGLES, clip, palette_.paddle_fill);
        painter.draw(lines_, GL_LINES, clip, palette_.paddle_lines);
    }
}

} // namespace sph
