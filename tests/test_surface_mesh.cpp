// The fluid surface (src/render/surface/, src/output/surface_export.*): the 2D
// region and the 3D level set's mesh sit where the particles' discs and
// spheres end, are closed, face out, carry the colour field to their
// vertices; the .ply's bytes follow its header and the .vdb reads back with
// OpenVDB; EGL and OSMesa draw the same surface and match the golden images;
// bad surface keys exit 2 naming the key. (The .ply read by VTK's own reader:
// tests/exports/check_surface_with_vtk.py.)
#include "output/image_compare.hpp"
#include "output/png_io.hpp"
#include "output/surface_export.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "render/surface/frame_surface.hpp"
#include "render/surface/reconstruct.hpp"
#include "scene/scene_setup.hpp"
#include "support/golden_frames.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>

#ifdef SPHCLIP_HAVE_OPENVDB
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#endif

using namespace sph;
namespace fs = std::filesystem;

namespace {

// A block of particles on a lattice of spacing s filling [0, side]^dim, the
// speed equal to x (a linear field).
Snapshot lattice_block(int dim, int per_side, double s) {
    Snapshot f;
    f.dimension = dim;
    const int nz = dim == 3 ? per_side : 1;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < per_side; ++j)
            for (int i = 0; i < per_side; ++i) {
                const double p[3] = {(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s};
                for (int a = 0; a < dim; ++a) {
                    f.position.push_back(p[a]);
                    f.velocity.push_back(a == 0 ? p[0] : 0);
                }
                f.density.push_back(1000);
                f.pressure.push_back(0);
                f.id.push_back(std::uint32_t(f.id.size()));
            }
    return f;
}

// Each undirected edge of the triangles, counted.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges(const std::vector<std::uint32_t>& t) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
    for (std::size_t k = 0; k < t.size(); k += 3)
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = t[k + e], b = t[k + (e + 1) % 3];
            ++count[{std::min(a, b), std::max(a, b)}];
        }
    return count;
}

} // namespace

TEST_CASE("2D: the filled region is the particles' discs' block, its outline closed", "[surface]") {
    const double s = 0.01;
    const Snapshot f = lattice_block(2, 20, s); // [0, 0.2]^2
    const Surface surface = reconstruct_surface(f, ColourField::velocity, s, SurfaceSettings{});
    const SurfaceMesh& m = surface.mesh;
    REQUIRE(m.dimension == 2);
    REQUIRE(!m.triangles.empty());
    double area = 0, lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
    for (std::size_t k = 0; k < m.triangles.size(); k += 3) {
        const float* a = &m.positions[3 * m.triangles[k]];
        const float* b = &m.positions[3 * m.triangles[k + 1]];
        const float* c = &m.positions[3 * m.triangles[k + 2]];
        area += 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    for (std::size_t v = 0; v < m.vertices(); ++v)
        for (int a = 0; a < 2; ++a) {
            lo[a] = std::min(lo[a], double(m.positions[3 * v + a]));
            hi[a] = std::max(hi[a], double(m.positions[3 * v + a]));
        }
    // The discs' block is 0.2 x 0.2; corners round off a little.
    CHECK(area == Approx(0.04).epsilon(0.03));
    for (int a = 0; a < 2; ++a) {
        CHECK(lo[a] == Approx(0).margin(0.3 * s));
        CHECK(hi[a] == Approx(0.2).margin(0.3 * s));
    }
    // Closed: every outline vertex ends exactly two segments.
    std::map<std::uint32_t, int> ends;
    for (std::uint32_t v : m.outline)
        ++ends[v];
    REQUIRE(!ends.empty());
    for (const auto& [v, count] : ends)
        CHECK(count == 2);
    // The colour field (speed = x) carried to the vertices: inside the block
    // the kernel average of a linear field is the field.
    for (std::size_t v = 0; v < m.vertices(); ++v) {
        const double x = m.positions[3 * v], y = m.positions[3 * v + 1];
        if (x > 3 * s && x < 0.2 - 3 * s && y > 3 * s && y < 0.2 - 3 * s)
            CHECK(m.scalar[v] == Approx(x).margin(1e-4));
    }
}

TEST_CASE("2D: two separate blocks give two regions", "[surface]") {
    const double s = 0.01;
    Snapshot f = lattice_block(2, 8, s);
    const Snapshot g = lattice_block(2, 8, s);
    for (std::size_t i = 0; i < g.size(); ++i) {
        f.position.push_back(g.position[2 * i] + 0.2);
        f.position.push_back(g.position[2 * i + 1]);
        f.velocity.push_back(0);
        f.velocity.push_back(0);
        f.density.push_back(1000);
        f.pressure.push_back(0);
        f.id.push_back(std::uint32_t(f.id.size()));
    }
    const SurfaceMesh m = reconstruct_surface(f, ColourField::velocity, s, SurfaceSettings{}).mesh;
    // No triangle spans the gap between 0.08 and 0.2.
    for (std::size_t k = 0; k < m.triangles.size(); ++k)
        CHECK(!(m.positions[3 * m.triangles[k]] > 0.1 && m.positions[3 * m.triangles[k]] < 0.18));
}

#ifdef SPHCLIP_HAVE_OPENVDB
TEST_CASE("3D: the level set's mesh is closed, faces out, and bounds the spheres' block",
          "[surface]") {
    const double s = 0.01;
    const Snapshot f = lattice_block(3, 12, s); // [0, 0.12]^3
    const Surface surface = reconstruct_surface(f, ColourField::velocity, s, SurfaceSettings{});
    const SurfaceMesh& m = surface.mesh;
    REQUIRE(surface.level_set);
    REQUIRE(m.vertices() > 100);
    // Closed and manifold: every edge shared by exactly two triangles.
    for (const auto& [edge, count] : edges(m.triangles))
        CHECK(count == 2);
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
    std::size_t outward = 0;
    for (std::size_t v = 0; v < m.vertices(); ++v) {
        double along = 0;
        for (int a = 0; a < 3; ++a) {
            const double p = m.positions[3 * v + a];
            lo[a] = std::min(lo[a], p);
            hi[a] = std::max(hi[a], p);
            along += (p - 0.06) * m.normals[3 * v + a];
        }
        outward += along > 0;
    }
    CHECK(outward == m.vertices());
    // Where the spheres of radius s / 2 end: the block [0, 0.12]^3, within
    // a voxel (the smoothing rounds the edges in).
    for (int a = 0; a < 3; ++a) {
        CHECK(lo[a] == Approx(0).margin(0.5 * s));
        CHECK(hi[a] == Approx(0.12).margin(0.5 * s));
    }
    // Speed = x carried to the vertices within a spacing.
    for (std::size_t v = 0; v < m.vertices(); ++v)
        CHECK(m.scalar[v] == Approx(m.positions[3 * v]).margin(s));
}

TEST_CASE("3D: the .vdb reads back with OpenVDB as the level set meshed", "[surface]") {
    test::TempFolder tmp;
    const double s = 0.01;
    const Surface surface =
        reconstruct_surface(lattice_block(3, 6, s), ColourField::velocity, s, SurfaceSettings{});
    const fs::path path = tmp / "surface.vdb";
    write_level_set(*surface.level_set, path);
    CHECK(!fs::exists(tmp / "surface.vdb.partial"));
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    openvdb::GridBase::Ptr base = file.readGrid("surface");
    file.close();
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    REQUIRE(grid);
    CHECK(grid->getGridClass() == openvdb::GRID_LEVEL_SET);
    CHECK(grid->voxelSize()[0] == Approx(0.5 * s));
    // Inside the block negative, outside positive, the surface between.
    auto accessor = grid->getConstAccessor();
    const auto inside = grid->transform().worldToIndexCellCentered(openvdb::Vec3d(0.03));
    const auto outside = grid->transform().worldToIndexCellCentered(openvdb::Vec3d(0.07));
    CHECK(accessor.getValue(inside) < 0);
    CHECK(accessor.getValue(outside) > 0);
    // The file's surface at zero is the drawn mesh: each vertex within a
    // tenth of a voxel of the file's zero level.
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
        sampler(accessor, grid->transform());
    for (std::size_t v = 0; v < surface.mesh.vertices(); ++v) {
        const float* p = &surface.mesh.positions[3 * v];
        CHECK(std::abs(sampler.wsSample(openvdb::Vec3d(p[0], p[1], p[2]))) < 0.05 * s);
    }
}
#endif

TEST_CASE("the .ply is binary little-endian with the bytes its header promises", "[surface]") {
    SurfaceMesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    m.scalar = {0, 0.5f, 1};
    m.triangles = {0, 1, 2};
    const std::string ply = ply_bytes(m, "speed", ColourMap::viridis, {0, 1});
    const std::string end = "end_header\n";
    const auto body = ply.find(end);
    REQUIRE(body != std::string::npos);
    const std::string header = ply.substr(0, body);
    CHECK(header.find("format binary_little_endian 1.0") != std::string::npos);
    CHECK(header.find("element vertex 3") != std::string::npos);
    CHECK(header.find("property float speed") != std::string::npos);
    CHECK(header.find("element face 1") != std::string::npos);
    CHECK(ply.size() - body - end.size() == 3 * (7 * 4 + 3) + (1 + 3 * 4));
    float y1 = 0;
    std::memcpy(&y1, ply.data() + body + end.size() + 31 + 4, 4);
    CHECK(y1 == 0.f);
}

namespace {

Scene tiny_surface_scene(int dimension) {
    return test::tiny_scene(dimension, {{"render.style", "surface"}});
}

} // namespace

TEST_CASE("surface frames: EGL and OSMesa agree pixel for pixel and match the goldens",
          "[surface][render]") {
    std::vector<int> dims{2};
    if (surface_3d_available())
        dims.push_back(3);
    for (int dim : dims) {
        INFO(dim << "D");
        const Scene scene = tiny_surface_scene(dim);
        const Image egl = test::render_scene(scene, "egl");
        const Image osmesa = test::render_scene(scene, "osmesa");
        REQUIRE(egl.width == osmesa.width);
        CHECK(egl.rgba == osmesa.rgba);
        test::check_against_golden(egl, dim == 2 ? "tiny_surface_2d" : "tiny_surface_3d");
        test::check_against_golden(osmesa, dim == 2 ? "tiny_surface_2d" : "tiny_surface_3d");
    }
}

TEST_CASE("bad surface keys exit 2 naming the key, and write nothing", "[surface][cli]") {
    test::TempFolder tmp;
    const std::vector<std::pair<std::string, std::string>> bad{
        {"render.style=blobs", "render.style"},
        {"render.surface.voxel=5", "render.surface.voxel"},
        {"render.surface.voxel=0", "render.surface.voxel"},
        {"render.surface.radius=0.2", "render.surface.radius"},
        {"render.surface.smoothing=-1", "render.surface.smoothing"},
    };
    for (const auto& [set, key] : bad) {
        INFO(set);
        const fs::path out = tmp / "out";
        const auto r = test::run_sphclip(
            tmp, {"run", "--set", set, "--out", out.string(), "--duration", "0.01", "--quiet"});
        CHECK(r.exit_code == 2);
        CHECK(r.output.find(key) != std::string::npos);
        CHECK(!fs::exists(out));
    }
}

TEST_CASE("the surface export writes a .ply per frame (and a .vdb in 3D)", "[surface][cli]") {
    test::TempFolder tmp;
    const fs::path out = tmp / "out";
    const std::string scene =
        (fs::path(SPHCLIP_SOURCE_DIR) / "scenes" / "dam_break_3d.json").string();
    const auto r = test::run_sphclip(
        tmp, {"run", scene, "--out", out.string(), "--export", "surface", "--no-png", "--no-mp4",
              "--duration", "0.02", "--fps", "50", "--set", "fluid.spacing=0.01", "--quiet"});
    if (!surface_3d_available()) {
        CHECK(r.exit_code == 2);
        CHECK(r.output.find("--export") != std::string::npos);
        return;
    }
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    for (const char* name : {"frame_00000.ply", "frame_00001.ply", "frame_00000.vdb"})
        CHECK(fs::file_size(out / "surface" / name) > 100);
    CHECK(!fs::exists(out / "particles"));
    for (const auto& entry : fs::directory_iterator(out / "surface"))
        CHECK(entry.path().extension() != ".partial");
}

TEST_CASE("with the surface style and the export, each frame's surface is reconstructed once",
          "[surface][render]") {
    std::vector<int> dims{2};
    if (surface_3d_available())
        dims.push_back(3);
    for (int dim : dims) {
        INFO(dim << "D");
        test::TempFolder tmp;
        const Scene scene = tiny_surface_scene(dim);
        const RenderSettings settings = make_render_settings(scene);
        Snapshot frame =
            dim == 2 ? test::initial_snapshot<2>(scene) : test::initial_snapshot<3>(scene);
        auto context = make_gl_context("osmesa");
        // As a run with both wires them: the export first, then the picture.
        const auto shared =
            std::make_shared<FrameSurface>(settings.field, settings.spacing, settings.surface);
        SurfaceExport exported(tmp.path(), settings, shared);
        FrameRenderer renderer(settings, shared);
        exported.write(frame);
        const Image picture = renderer.render(frame);
        CHECK(shared->reconstructions() == 1);
        // The next frame is a new surface, again made once.
        frame.frame = 1;
        frame.steps = 3;
        exported.write(frame);
        const Image next = renderer.render(frame);
        CHECK(shared->reconstructions() == 2);
        // The same bytes as each made alone: the picture of a renderer with a
        // surface of its own, the mesh of a reconstruction of its own.
        FrameRenderer alone(settings);
        CHECK(alone.render(frame).rgba == next.rgba);
        CHECK(picture.rgba.size() == next.rgba.size());
        const Surface own =
            reconstruct_surface(frame, settings.field, settings.spacing, settings.surface);
        CHECK(test::read_text(tmp / "surface" / "frame_00001.ply") ==
              ply_bytes(own.mesh, "speed", settings.colour_map, settings.range));
    }
}

TEST_CASE("with shadows on, the surface casts its shadow on the floor as the spheres do",
          "[surface][render]") {
    if (!surface_3d_available())
        return;
    const Scene scene = tiny_surface_scene(3);
    const Snapshot frame = test::initial_snapshot<3>(scene);
    Snapshot empty = frame;
    empty.position.clear();
    empty.velocity.clear();
    empty.density.clear();
    empty.pressure.clear();
    empty.id.clear();
    empty.buried.clear();
    auto context = make_gl_context("osmesa");
    RenderSettings lit = make_render_settings(scene);
    lit.shadows = true;
    RenderSettings unlit = lit;
    unlit.shadows = false;
    // Pixels the shadows darken by more than a few levels, and those they
    // brighten at all beyond rounding.
    auto darkened = [&](const Snapshot& f) {
        FrameRenderer with(lit), without(unlit);
        const Image a = with.render(f), b = without.render(f);
        REQUIRE(a.rgba.size() == b.rgba.size());
        std::size_t darker = 0, brighter = 0;
        for (std::size_t p = 0; p + 3 < a.rgba.size(); p += 4) {
            int sum = 0;
            for (int c = 0; c < 3; ++c)
                sum += int(a.rgba[p + c]) - int(b.rgba[p + c]);
            darker += sum < -12;
            brighter += sum > 6;
        }
        return std::pair{darker, brighter};
    };
    // The floor with nothing above it is the same with shadows or without;
    // with the surface above it, a patch of it is darker (the mesh drew its
    // depth into the shadow map), and nothing lighter.
    const auto [bare_darker, bare_brighter] = darkened(empty);
    CHECK(bare_darker == 0);
    CHECK(bare_brighter == 0);
    const auto [darker, brighter] = darkened(frame);
    INFO(darker << " darker, " << brighter << " brighter of 320 x 180");
    CHECK(darker > 200);
    CHECK(brighter < darker / 20);
}
