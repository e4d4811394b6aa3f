#include "render/frame_renderer.hpp"

#include "io/scene_setup.hpp"
#include "render/colour_maps.hpp"
#include "render/sphere_geometry.hpp"
#include "render/text.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <embedded_shaders.hpp>
#include <fmt/format.h>
#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <stdexcept>
#include <vector>

namespace sph {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

GLuint compile(GLenum stage, std::string_view common, std::string_view body) {
    const std::string source = "#version 450 core\n" + std::string(common) + std::string(body);
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("shader compilation failed: ") + log);
    }
    return shader;
}

GLuint link(std::string_view vertex, std::string_view fragment, std::string_view common) {
    const GLuint vs = compile(GL_VERTEX_SHADER, common, vertex);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, common, fragment);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw std::runtime_error(std::string("shader link failed: ") + log);
    }
    return program;
}

void check_gl(const char* where) {
    if (const GLenum error = glGetError(); error != GL_NO_ERROR)
        throw std::runtime_error(fmt::format("OpenGL error 0x{:04x} in {}", error, where));
}

// One overlay vertex: position and colour-map coordinate (< 0: flat colour).
struct OverlayVertex {
    float x, y, z, ramp;
};

// A box from lo to hi: in 2D (flat) a filled rectangle at depth `behind` with
// its outline, in 3D its edges.
void append_box(const glm::vec3& lo, const glm::vec3& hi, bool flat, float behind,
                std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& fill) {
    auto line = [&](glm::vec3 p, glm::vec3 q) {
        lines.push_back({p.x, p.y, p.z, -1});
        lines.push_back({q.x, q.y, q.z, -1});
    };
    if (flat) {
        const glm::vec3 c[4] = {{lo.x, lo.y, 0}, {hi.x, lo.y, 0}, {hi.x, hi.y, 0}, {lo.x, hi.y, 0}};
        for (int k = 0; k < 4; ++k)
            line(c[k], c[(k + 1) % 4]);
        for (int k : {0, 1, 2, 0, 2, 3})
            fill.push_back({c[k].x, c[k].y, behind, -1});
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
            line(p, q);
        }
}

// The paddles at time t, relative to `origin`, as boxes (append_box).
void append_paddles(const RenderSettings& s, double t, const glm::dvec3& origin, float behind,
                    std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& fill) {
    const bool flat = s.dimension == 2;
    for (const Paddle<3>& paddle : s.paddles) {
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
void append_obstacles(const RenderSettings& s, const glm::dvec3& origin, float behind,
                      std::vector<OverlayVertex>& lines, std::vector<OverlayVertex>& fill) {
    constexpr int segments = 64;
    const bool flat = s.dimension == 2;
    auto at = [&](const Vec3& p) {
        return glm::vec3(float(p[0] - origin.x), float(p[1] - origin.y),
                         flat ? 0.f : float(p[2] - origin.z));
    };
    auto line = [&](glm::vec3 p, glm::vec3 q) {
        lines.push_back({p.x, p.y, p.z, -1});
        lines.push_back({q.x, q.y, q.z, -1});
    };
    auto triangle = [&](glm::vec3 p, glm::vec3 q, glm::vec3 r) {
        for (const glm::vec3& v : {p, q, r})
            fill.push_back({v.x, v.y, behind, -1});
    };
    for (const SceneObstacle& o : s.obstacles) {
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
                line(point(k), point(k + 1));
                if (flat)
                    triangle(centre, point(k), point(k + 1));
            }
        }
    }
}

// The mesh obstacles' triangles relative to `origin`, each vertex followed by
// its face's normal (x, y, z, nx, ny, nz): flat shading shows the facets the
// simulation sees.
std::vector<float> mesh_obstacle_triangles(const RenderSettings& s, const glm::dvec3& origin) {
    std::vector<float> out;
    for (const SceneObstacle& o : s.obstacles) {
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

// How a sphere is drawn, by its width in the image (RenderSettings).
enum Outline : int { ray_cast_square, ray_cast_triangle, flat_disc };

// Orders the first n instances (x, y, z, scalar each) by their depth keys,
// nearest first, in 4096 classes of equal depth range: a counting sort, one
// pass to count and one to place, stable within a class.
void sort_by_depth(std::vector<float>& instances, std::size_t n, const std::vector<float>& keys,
                   std::vector<float>& scratch, std::vector<std::uint32_t>& starts) {
    if (n < 2)
        return;
    constexpr std::size_t classes = 4096;
    const auto [lo, hi] = std::minmax_element(keys.begin(), keys.begin() + std::ptrdiff_t(n));
    const float scale = *hi > *lo ? float(classes - 1) / (*hi - *lo) : 0.f;
    auto class_of = [&](std::size_t i) {
        return std::size_t((keys[i] - *lo) * scale);
    };
    starts.assign(classes + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
        ++starts[class_of(i) + 1];
    for (std::size_t c = 0; c < classes; ++c)
        starts[c + 1] += starts[c];
    scratch.resize(n * 4);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t to = starts[class_of(i)]++;
        std::copy_n(instances.begin() + std::ptrdiff_t(i * 4), 4,
                    scratch.begin() + std::ptrdiff_t(to * 4));
    }
    std::copy_n(scratch.begin(), n * 4, instances.begin());
}

} // namespace

RenderSettings make_render_settings(const Scene& scene) {
    RenderSettings r;
    r.width = scene.render.size[0];
    r.height = scene.render.size[1];
    r.dimension = scene.dimension;
    r.field = scene.render.colour;
    r.spheres = scene.render.spheres;
    r.radius = 0.5 * scene.fluid.spacing;
    for (int a = 0; a < scene.dimension; ++a) {
        r.domain_min[a] = scene.domain.min[a];
        r.domain_max[a] = scene.domain.max[a];
    }
    r.obstacles = scene.effects.obstacles;
    r.paddles = make_paddles<3>(scene);
    // Physical scales of the scene for ranges it does not fix.
    const double height = r.domain_max.y - r.domain_min.y;
    double g = 0;
    if (scene.effects.gravity)
        for (int a = 0; a < scene.dimension; ++a)
            g += scene.effects.gravity->acceleration[a] * scene.effects.gravity->acceleration[a];
    g = std::sqrt(g);
    double block_speed = 0;
    for (const auto& b : scene.fluid.blocks)
        block_speed =
            std::max(block_speed, std::hypot(b.velocity[0], b.velocity[1], b.velocity[2]));
    const double rho0 = scene.material.rest_density;
    if (r.field == "velocity") {
        r.label = "speed (m/s)";
        r.colour_map = "viridis";
        // Nothing in the scene sets a speed (no gravity, a block at rest, as
        // a drop pulled round by surface tension): a gentle 0.1 m/s.
        const double top = std::sqrt(2 * g * height) + block_speed;
        r.range = {0, top > 0 ? top : 0.1};
    } else if (r.field == "density") {
        r.label = "density (kg/m^3)";
        r.colour_map = "diverging";
        r.range = {0.97 * rho0, 1.03 * rho0};
    } else {
        r.label = "pressure (Pa)";
        r.colour_map = "turbo";
        const double top = rho0 * g * height;
        r.range = {0, top > 0 ? top : 0.5 * rho0 * 0.1 * 0.1}; // as for speed
    }
    if (scene.render.colour_map != "auto")
        r.colour_map = scene.render.colour_map;
    if (scene.render.range)
        r.range = *scene.render.range;

    r.fov = scene.render.camera.fov;
    const glm::dvec3 centre = 0.5 * (r.domain_min + r.domain_max);
    r.camera_target = centre;
    if (scene.render.camera.target)
        r.camera_target = {(*scene.render.camera.target)[0], (*scene.render.camera.target)[1],
                           (*scene.render.camera.target)[2]};
    if (scene.render.camera.position) {
        r.camera_position = {(*scene.render.camera.position)[0], (*scene.render.camera.position)[1],
                             (*scene.render.camera.position)[2]};
    } else {
        // From the front, right and above, at the distance where the domain's
        // bounding sphere would just fit the vertical field of view; a box
        // fills less than its sphere, so come a little closer.
        const double radius = 0.5 * glm::length(r.domain_max - r.domain_min);
        const double distance = 0.85 * radius / std::sin(glm::radians(0.5 * r.fov));
        r.camera_position = r.camera_target + distance * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
    }
    r.cull_buried = scene.dimension == 3 && scene.render.cull_buried;
    return r;
}

struct FrameRenderer::Gl {
    GLuint impostor_program = 0, mesh_program = 0, overlay_program = 0, solid_program = 0;
    GLuint disc_program = 0; // flat discs, quads or points (flat_below_px > 0)
    GLuint impostor_vao = 0, triangle_vao = 0, mesh_vao = 0, overlay_vao = 0, solid_vao = 0,
           point_vao = 0;
    GLuint quad_buffer = 0, triangle_buffer = 0, instance_buffer = 0, mesh_vertex_buffer = 0,
           mesh_index_buffer = 0;
    GLuint overlay_buffer = 0, solid_buffer = 0;
    GLsizei solid_vertex_count = 0; // mesh obstacles, uploaded once
    GLsizei mesh_index_count = 0;
    std::size_t instance_capacity = 0;
    GLuint colour_map = 0;
    GLuint msaa_fbo = 0, msaa_colour = 0, msaa_depth = 0;
    GLuint resolve_fbo = 0, resolve_colour = 0;
    // The drawn particles' x, y, z, scalar by how they are drawn (Outline),
    // and their depth keys when sorted; scratch reused from frame to frame.
    std::array<std::vector<float>, 3> instances, depth_keys;
    std::vector<float> sorted;
    std::vector<std::uint32_t> bucket_starts;
    std::vector<OverlayVertex> lines, overlay_triangles;
    std::vector<float> text;

    ~Gl() {
        glDeleteProgram(impostor_program);
        glDeleteProgram(mesh_program);
        glDeleteProgram(overlay_program);
        glDeleteProgram(solid_program);
        glDeleteProgram(disc_program);
        const GLuint vaos[] = {impostor_vao, triangle_vao, mesh_vao,
                               overlay_vao,  solid_vao,    point_vao};
        glDeleteVertexArrays(6, vaos);
        const GLuint buffers[] = {quad_buffer,        triangle_buffer,   instance_buffer,
                                  mesh_vertex_buffer, mesh_index_buffer, overlay_buffer,
                                  solid_buffer};
        glDeleteBuffers(7, buffers);
        glDeleteTextures(1, &colour_map);
        const GLuint framebuffers[] = {msaa_fbo, resolve_fbo};
        glDeleteFramebuffers(2, framebuffers);
        const GLuint renderbuffers[] = {msaa_colour, msaa_depth, resolve_colour};
        glDeleteRenderbuffers(3, renderbuffers);
    }
};

FrameRenderer::FrameRenderer(const RenderSettings& settings)
    : settings_(settings), gl_(std::make_unique<Gl>()) {
    Gl& g = *gl_;
    const std::string impostor_defines =
        settings.conservative_depth ? "#define CONSERVATIVE_DEPTH\n" : "";
    g.impostor_program = link(shaders::sphere_impostor_vert, shaders::sphere_impostor_frag,
                              impostor_defines + std::string(shaders::lighting));
    if (settings.flat_below_px > 0) {
        const std::string disc_defines = settings.flat_as_points ? "#define POINTS\n" : "";
        g.disc_program = link(shaders::sphere_disc_vert, shaders::sphere_disc_frag,
                              disc_defines + std::string(shaders::lighting));
    }
    g.mesh_program = link(shaders::sphere_mesh_vert, shaders::sphere_mesh_frag, shaders::lighting);
    g.overlay_program = link(shaders::overlay_vert, shaders::overlay_frag, "");

    // Per-particle data, shared by both sphere techniques: x, y, z, scalar.
    glGenBuffers(1, &g.instance_buffer);
    auto bind_instances = [&g] {
        glBindBuffer(GL_ARRAY_BUFFER, g.instance_buffer);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 16, nullptr);
        glVertexAttribDivisor(1, 1);
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 16, reinterpret_cast<void*>(12));
        glVertexAttribDivisor(2, 1);
    };

    // The impostor's outlines around the unit circle: a square (a strip of
    // two triangles), and the equilateral triangle whose inscribed circle it
    // is (30% more area, half the triangles).
    auto outline = [&bind_instances](GLuint& vao, GLuint& buffer, const std::vector<float>& xy) {
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
        glGenBuffers(1, &buffer);
        glBindBuffer(GL_ARRAY_BUFFER, buffer);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(xy.size() * sizeof(float)), xy.data(),
                     GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
        bind_instances();
    };
    outline(g.impostor_vao, g.quad_buffer, {-1, -1, 1, -1, -1, 1, 1, 1});
    const float sqrt3 = std::sqrt(3.f);
    outline(g.triangle_vao, g.triangle_buffer, {0, 2, -sqrt3, -1, sqrt3, -1});

    // Point sprites: the same per-particle data, one vertex per particle.
    glGenVertexArrays(1, &g.point_vao);
    glBindVertexArray(g.point_vao);
    bind_instances();
    glVertexAttribDivisor(1, 0);
    glVertexAttribDivisor(2, 0);

    glGenVertexArrays(1, &g.mesh_vao);
    glBindVertexArray(g.mesh_vao);
    const SphereMesh mesh = make_icosphere(settings.mesh_subdivisions);
    glGenBuffers(1, &g.mesh_vertex_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, g.mesh_vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof mesh.vertices[0]),
                 mesh.vertices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glGenBuffers(1, &g.mesh_index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.mesh_index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    g.mesh_index_count = GLsizei(mesh.indices.size());
    bind_instances();

    glGenVertexArrays(1, &g.overlay_vao);
    glBindVertexArray(g.overlay_vao);
    glGenBuffers(1, &g.overlay_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, g.overlay_buffer);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                          reinterpret_cast<void*>(12));

    // Mesh obstacles never move: their triangles are uploaded once.
    const std::vector<float> solid =
        mesh_obstacle_triangles(settings, 0.5 * (settings.domain_min + settings.domain_max));
    if (!solid.empty()) {
        g.solid_program = link(shaders::solid_vert, shaders::solid_frag, shaders::lighting);
        glGenVertexArrays(1, &g.solid_vao);
        glBindVertexArray(g.solid_vao);
        glGenBuffers(1, &g.solid_buffer);
        glBindBuffer(GL_ARRAY_BUFFER, g.solid_buffer);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(solid.size() * sizeof(float)), solid.data(),
                     GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                              reinterpret_cast<void*>(3 * sizeof(float)));
        g.solid_vertex_count = GLsizei(solid.size() / 6);
    }
    glBindVertexArray(0);

    const auto table = colour_map_table(settings.colour_map, 256);
    glGenTextures(1, &g.colour_map);
    glBindTexture(GL_TEXTURE_1D, g.colour_map);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage1D(GL_TEXTURE_1D, 0, GL_RGB8, 256, 0, GL_RGB, GL_UNSIGNED_BYTE, table.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);

    // Draw multisampled, resolve into a plain buffer for reading back.
    const int w = settings.width, h = settings.height;
    glGenRenderbuffers(1, &g.msaa_colour);
    glBindRenderbuffer(GL_RENDERBUFFER, g.msaa_colour);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, settings.samples, GL_RGBA8, w, h);
    glGenRenderbuffers(1, &g.msaa_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, g.msaa_depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, settings.samples, GL_DEPTH_COMPONENT24, w, h);
    glGenFramebuffers(1, &g.msaa_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g.msaa_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g.msaa_colour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g.msaa_depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the multisampled framebuffer is incomplete");
    glGenRenderbuffers(1, &g.resolve_colour);
    glBindRenderbuffer(GL_RENDERBUFFER, g.resolve_colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glGenFramebuffers(1, &g.resolve_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g.resolve_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              g.resolve_colour);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the resolve framebuffer is incomplete");
    check_gl("renderer set-up");
}

FrameRenderer::~FrameRenderer() = default;

Image FrameRenderer::render(const Snapshot& frame) {
    Gl& g = *gl_;
    const RenderSettings& s = settings_;
    const int w = s.width, h = s.height;
    const auto start = Clock::now();

    // Positions relative to the domain centre: floats stay exact far from the origin.
    const glm::dvec3 origin = 0.5 * (s.domain_min + s.domain_max);
    const int dim = frame.dimension;

    // Cameras: 2D looks at the plane with the domain fitted left of the colour
    // bar; 3D uses the scene's perspective camera.
    const bool orthographic = s.dimension == 2;
    glm::mat4 view(1.f), projection(1.f);
    // Overlay layout scales with the image: room on the right for the colour
    // bar and its labels, a caption line on top.
    const float text_scale = std::max(1.f, std::round(float(h) / 360.f));
    const double bar_space = std::max(75.0, 150.0 * w / 1280.0);
    const double margin = std::max(8.0, 24.0 * h / 720.0);
    const double caption_space = 18.0 * text_scale;
    if (orthographic) {
        const glm::dvec3 size = s.domain_max - s.domain_min;
        const double available_w = std::max(1.0, w - bar_space - 2 * margin);
        const double available_h = std::max(1.0, h - caption_space - 2 * margin);
        const double scale = std::min(available_w / size.x, available_h / size.y); // px per m
        const double left =
            s.domain_min.x - origin.x - (margin + 0.5 * (available_w - scale * size.x)) / scale;
        const double bottom =
            s.domain_min.y - origin.y - (margin + 0.5 * (available_h - scale * size.y)) / scale;
        const double depth = 10 + 4 * s.radius;
        projection = glm::ortho(left, left + w / scale, bottom, bottom + h / scale, -depth, depth);
    } else {
        view = glm::lookAt(glm::vec3(s.camera_position - origin),
                           glm::vec3(s.camera_target - origin), glm::vec3(0, 1, 0));
        const double distance = glm::length(s.camera_position - s.camera_target);
        const double extent = glm::length(s.domain_max - s.domain_min);
        projection = glm::perspective(glm::radians(float(s.fov)), float(w) / float(h),
                                      float(std::max(1e-4 * distance, 0.01 * s.radius)),
                                      float(4 * (distance + extent)));
        // Centre the view in the part of the image left of the colour bar.
        projection =
            glm::translate(glm::mat4(1.f), glm::vec3(float(-bar_space / w), 0.f, 0.f)) * projection;
    }

    // Which particles to draw and how, seen through the camera: skip those
    // buried in the fluid and those whose sphere lies wholly outside the view,
    // and group the rest by how they are drawn (Outline), from their width in
    // the image.
    const glm::dmat4 clip_from_world(projection * view);
    auto clip_row = [&clip_from_world](int r) {
        return glm::dvec4(clip_from_world[0][r], clip_from_world[1][r], clip_from_world[2][r],
                          clip_from_world[3][r]);
    };
    // The view's six planes from the clip matrix (Gribb and Hartmann 2001,
    // "Fast extraction of viewing frustum planes from the world-view-projection
    // matrix"): w +- x, w +- y, w +- z, each >= 0 inside; normalised, so a
    // plane's value at a point is its distance from the plane.
    std::array<glm::dvec4, 6> planes;
    for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
            const glm::dvec4 plane = clip_row(3) + (side ? -1.0 : 1.0) * clip_row(a);
            planes[std::size_t(2 * a + side)] = plane / glm::length(glm::dvec3(plane));
        }
    const glm::dvec4 depth_row = clip_row(2), w_row = clip_row(3);
    // A sphere whose every point is at least a little outside one plane colours
    // no pixel: the impostor's fragments all lie within its silhouette, the
    // mesh within the sphere. The margin covers the GPU's float round-off.
    const double cull_margin = 1.01 * s.radius + 1e-6 * glm::length(s.domain_max - s.domain_min);
    // A sphere's image is r P[1][1] h / w pixels across (P[1][1]: view-space y
    // to clip y; w: the distance in front of the eye, 1 in 2D).
    const double px_per_radius = projection[1][1] * h;
    const bool cull_buried = s.cull_buried && frame.buried.size() == frame.size();
    const bool impostor = s.spheres == "impostor";
    const bool may_flat = impostor && s.flat_below_px > 0;
    const bool may_triangle = impostor && s.triangles_below_px > 0;
    for (int group = 0; group < 3; ++group)
        if (group == ray_cast_square || (group == ray_cast_triangle && may_triangle) ||
            (group == flat_disc && may_flat)) {
            g.instances[group].resize(frame.size() * 4);
            if (s.sort_front_to_back)
                g.depth_keys[group].resize(frame.size());
        }
    std::array<std::size_t, 3> count{};
    std::size_t outside = 0;
    // The field is chosen once, not per particle.
    const bool speed = s.field == "velocity";
    const std::vector<double>& field = s.field == "density" ? frame.density : frame.pressure;
    for (std::size_t i = 0; i < frame.size(); ++i) {
        if (cull_buried && frame.buried[i])
            continue;
        glm::dvec4 p(0, 0, 0, 1);
        for (int a = 0; a < dim; ++a)
            p[a] = frame.position[i * dim + a] - origin[a];
        // Distance inside the nearest side plane (left, right, bottom, top).
        double inside = std::numeric_limits<double>::max();
        if (s.cull_outside_view) {
            bool outside_a_plane = false;
            for (std::size_t k = 0; k < planes.size(); ++k) {
                const double distance = glm::dot(planes[k], p);
                outside_a_plane = outside_a_plane || distance < -cull_margin;
                if (k < 4)
                    inside = std::min(inside, distance);
            }
            if (outside_a_plane) {
                ++outside;
                continue;
            }
        }
        double scalar = 0;
        if (speed) {
            for (int a = 0; a < dim; ++a)
                scalar += frame.velocity[i * dim + a] * frame.velocity[i * dim + a];
            scalar = std::sqrt(scalar);
        } else {
            scalar = field[i];
        }
        // By the sphere's width in the image (r px_per_radius / w pixels); a
        // point sprite also needs its whole disc in view, as GL drops a point
        // whose centre is outside it.
        int group = ray_cast_square;
        if (may_flat || may_triangle) {
            const double w_clip = glm::dot(w_row, p), width_times_w = s.radius * px_per_radius;
            if (w_clip > 0 && may_flat && width_times_w < s.flat_below_px * w_clip &&
                (!s.flat_as_points || (s.cull_outside_view && inside > cull_margin)))
                group = flat_disc;
            else if (w_clip > 0 && may_triangle && width_times_w < s.triangles_below_px * w_clip)
                group = ray_cast_triangle;
        }
        std::vector<float>& out = g.instances[group];
        const std::size_t k = count[group]++;
        for (int a = 0; a < 3; ++a)
            out[k * 4 + std::size_t(a)] = float(p[a]);
        out[k * 4 + 3] = float(scalar);
        if (s.sort_front_to_back)
            g.depth_keys[group][k] = float(glm::dot(depth_row, p));
    }
    if (s.sort_front_to_back)
        for (int group = 0; group < 3; ++group)
            sort_by_depth(g.instances[group], count[group], g.depth_keys[group], g.sorted,
                          g.bucket_starts);
    drawn_ = count[ray_cast_square] + count[ray_cast_triangle] + count[flat_disc];
    flat_ = count[flat_disc];
    outside_view_ = outside;
    timings_.fill_seconds = seconds_since(start);

    glBindFramebuffer(GL_FRAMEBUFFER, g.msaa_fbo);
    glViewport(0, 0, w, h);
    glClearColor(0.08f, 0.09f, 0.11f, 1.f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_MULTISAMPLE);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_1D, g.colour_map);

    if (drawn_ > 0) {
        // One buffer: the squares, the triangles, then the flat discs.
        glBindBuffer(GL_ARRAY_BUFFER, g.instance_buffer);
        if (drawn_ > g.instance_capacity) {
            g.instance_capacity = drawn_ + drawn_ / 4;
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(g.instance_capacity * 16), nullptr,
                         GL_STREAM_DRAW);
        }
        std::array<std::size_t, 3> first{};
        for (int group = 0; group < 3; ++group) {
            first[group] = group == 0 ? 0 : first[group - 1] + count[group - 1];
            glBufferSubData(GL_ARRAY_BUFFER, GLintptr(first[group] * 16),
                            GLsizeiptr(count[group] * 16), g.instances[group].data());
        }
        auto use = [&](GLuint program) {
            glUseProgram(program);
            glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                               glm::value_ptr(view));
            glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                               glm::value_ptr(projection));
            glUniform1f(glGetUniformLocation(program, "u_radius"), float(s.radius));
            glUniform1i(glGetUniformLocation(program, "u_orthographic"), orthographic);
            glUniform1i(glGetUniformLocation(program, "u_colour_map"), 0);
            glUniform2f(glGetUniformLocation(program, "u_range"), float(s.range[0]),
                        float(s.range[1]));
        };
        if (!impostor) {
            use(g.mesh_program);
            glBindVertexArray(g.mesh_vao);
            glDrawElementsInstanced(GL_TRIANGLES, g.mesh_index_count, GL_UNSIGNED_INT, nullptr,
                                    GLsizei(count[ray_cast_square]));
        } else {
            use(g.impostor_program);
            if (count[ray_cast_square] > 0) {
                glBindVertexArray(g.impostor_vao);
                glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count[ray_cast_square]));
            }
            if (count[ray_cast_triangle] > 0) {
                glBindVertexArray(g.triangle_vao);
                glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3,
                                                  GLsizei(count[ray_cast_triangle]),
                                                  GLuint(first[ray_cast_triangle]));
            }
        }
        if (count[flat_disc] > 0) {
            use(g.disc_program);
            glUniform1f(glGetUniformLocation(g.disc_program, "u_viewport_height"), float(h));
            if (s.flat_as_points) {
                glEnable(GL_PROGRAM_POINT_SIZE);
                glBindVertexArray(g.point_vao);
                glDrawArrays(GL_POINTS, GLint(first[flat_disc]), GLsizei(count[flat_disc]));
            } else {
                glBindVertexArray(g.triangle_vao);
                glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3, GLsizei(count[flat_disc]),
                                                  GLuint(first[flat_disc]));
            }
        }
    }

    // Mesh obstacles, solid and lit like the particles, depth-tested with them.
    if (g.solid_vertex_count > 0 && !orthographic) {
        glUseProgram(g.solid_program);
        glUniformMatrix4fv(glGetUniformLocation(g.solid_program, "u_view"), 1, GL_FALSE,
                           glm::value_ptr(view));
        glUniformMatrix4fv(glGetUniformLocation(g.solid_program, "u_projection"), 1, GL_FALSE,
                           glm::value_ptr(projection));
        glUniform3f(glGetUniformLocation(g.solid_program, "u_colour"), 0.62f, 0.6f, 0.56f);
        glBindVertexArray(g.solid_vao);
        glDrawArrays(GL_TRIANGLES, 0, g.solid_vertex_count);
    }

    // The domain box, depth-tested so the fluid hides its far edges.
    g.lines.clear();
    const glm::vec3 lo(s.domain_min - origin), hi(s.domain_max - origin);
    if (orthographic) {
        const glm::vec3 c[4] = {{lo.x, lo.y, 0}, {hi.x, lo.y, 0}, {hi.x, hi.y, 0}, {lo.x, hi.y, 0}};
        for (int k = 0; k < 4; ++k) {
            g.lines.push_back({c[k].x, c[k].y, c[k].z, -1});
            g.lines.push_back({c[(k + 1) % 4].x, c[(k + 1) % 4].y, 0, -1});
        }
    } else {
        for (int a = 0; a < 3; ++a)
            for (int corner = 0; corner < 4; ++corner) {
                glm::vec3 p = lo, q;
                const int b = (a + 1) % 3, c = (a + 2) % 3;
                p[b] = corner & 1 ? hi[b] : lo[b];
                p[c] = corner & 2 ? hi[c] : lo[c];
                q = p;
                q[a] = hi[a];
                g.lines.push_back({p.x, p.y, p.z, -1});
                g.lines.push_back({q.x, q.y, q.z, -1});
            }
    }
    g.overlay_triangles.clear();
    append_obstacles(s, origin, float(-2 * s.radius), g.lines, g.overlay_triangles);
    glUseProgram(g.overlay_program);
    glBindVertexArray(g.overlay_vao);
    glUniform1i(glGetUniformLocation(g.overlay_program, "u_colour_map"), 0);
    auto draw_overlay = [&](const std::vector<OverlayVertex>& vertices, GLenum mode,
                            const glm::mat4& transform, glm::vec4 colour) {
        if (vertices.empty())
            return;
        glBindBuffer(GL_ARRAY_BUFFER, g.overlay_buffer);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(OverlayVertex)),
                     vertices.data(), GL_STREAM_DRAW);
        glUniformMatrix4fv(glGetUniformLocation(g.overlay_program, "u_transform"), 1, GL_FALSE,
                           glm::value_ptr(transform));
        glUniform4fv(glGetUniformLocation(g.overlay_program, "u_colour"), 1,
                     glm::value_ptr(colour));
        glDrawArrays(mode, 0, GLsizei(vertices.size()));
    };
    draw_overlay(g.overlay_triangles, GL_TRIANGLES, projection * view, {0.3f, 0.32f, 0.36f, 1.f});
    draw_overlay(g.lines, GL_LINES, projection * view, {0.55f, 0.58f, 0.62f, 1.f});
    // Paddles in a warmer grey than the static solids: the parts that move.
    if (!s.paddles.empty()) {
        g.lines.clear();
        g.overlay_triangles.clear();
        append_paddles(s, frame.time, origin, float(-2 * s.radius), g.lines, g.overlay_triangles);
        draw_overlay(g.overlay_triangles, GL_TRIANGLES, projection * view,
                     {0.45f, 0.38f, 0.3f, 1.f});
        draw_overlay(g.lines, GL_LINES, projection * view, {0.78f, 0.66f, 0.5f, 1.f});
    }

    // Colour bar, its labels and the caption, in pixels (y down).
    glDisable(GL_DEPTH_TEST);
    const glm::mat4 pixels = glm::ortho(0.f, float(w), float(h), 0.f, -1.f, 1.f);
    const float bar_x = float(w - bar_space) + 8.f * text_scale, bar_w = 9.f * text_scale;
    const float bar_top = float(caption_space + margin) + 10.f * text_scale;
    const float bar_bottom = float(h - margin) - 5.f * text_scale;
    g.overlay_triangles = {{bar_x, bar_bottom, 0, 0},      {bar_x + bar_w, bar_bottom, 0, 0},
                           {bar_x + bar_w, bar_top, 0, 1}, {bar_x, bar_bottom, 0, 0},
                           {bar_x + bar_w, bar_top, 0, 1}, {bar_x, bar_top, 0, 1}};
    draw_overlay(g.overlay_triangles, GL_TRIANGLES, pixels, {1, 1, 1, 1});
    g.lines = {{bar_x, bar_top, 0, -1},
               {bar_x + bar_w, bar_top, 0, -1},
               {bar_x + bar_w, bar_top, 0, -1},
               {bar_x + bar_w, bar_bottom, 0, -1},
               {bar_x + bar_w, bar_bottom, 0, -1},
               {bar_x, bar_bottom, 0, -1},
               {bar_x, bar_bottom, 0, -1},
               {bar_x, bar_top, 0, -1}};
    for (int k = 0; k <= 4; ++k) {
        const float y = bar_bottom + (bar_top - bar_bottom) * float(k) / 4.f;
        g.lines.push_back({bar_x + bar_w, y, 0, -1});
        g.lines.push_back({bar_x + bar_w + 2.5f * text_scale, y, 0, -1});
    }
    draw_overlay(g.lines, GL_LINES, pixels, {0.85f, 0.86f, 0.88f, 1.f});

    g.text.clear();
    const float glyph_h = 7.f * text_scale;
    for (int k = 0; k <= 4; ++k) {
        const double value = s.range[0] + (s.range[1] - s.range[0]) * k / 4.0;
        const float y = bar_bottom + (bar_top - bar_bottom) * float(k) / 4.f - 0.5f * glyph_h;
        append_text_triangles(fmt::format("{:.4g}", value), bar_x + bar_w + 4.5f * text_scale, y,
                              text_scale, g.text);
    }
    const float label_w = text_width(s.label, text_scale);
    append_text_triangles(s.label, std::min(bar_x, float(w) - label_w - 4.f * text_scale),
                          bar_top - 2.5f * glyph_h, text_scale, g.text);
    append_text_triangles(fmt::format("t = {:.3f} s    frame {}", frame.time, frame.frame),
                          float(margin), float(margin) * 0.5f + 2.f * text_scale, text_scale,
                          g.text);
    g.overlay_triangles.clear();
    for (std::size_t k = 0; k + 1 < g.text.size(); k += 2)
        g.overlay_triangles.push_back({g.text[k], g.text[k + 1], 0, -1});
    draw_overlay(g.overlay_triangles, GL_TRIANGLES, pixels, {0.9f, 0.91f, 0.93f, 1.f});
    glFinish();
    timings_.draw_seconds = seconds_since(start);

    // Resolve the samples, read back, and turn the rows top-down.
    const auto readback_start = Clock::now();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.msaa_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g.resolve_fbo);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.resolve_fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    Image image(w, h);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    const std::size_t row = std::size_t(w) * 4;
    std::vector<std::uint8_t> swap(row);
    for (int y = 0; y < h / 2; ++y) {
        std::uint8_t* a = image.rgba.data() + std::size_t(y) * row;
        std::uint8_t* b = image.rgba.data() + std::size_t(h - 1 - y) * row;
        std::copy(a, a + row, swap.data());
        std::copy(b, b + row, a);
        std::copy(swap.begin(), swap.end(), b);
    }
    check_gl("frame rendering");
    timings_.readback_seconds = seconds_since(readback_start);
    return image;
}

} // namespace sph
