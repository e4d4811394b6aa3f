// The 3D surface with OpenVDB (reconstruct.hpp): particles to a narrow-band
// level set, smoothed and eroded, meshed at zero; and the .vdb export.
// Built as the module libsphclip_vdb.so (level_set_module.hpp), which
// exports only the table at the end.
#include "render/surface/level_set_module.hpp"
#include "sph/wall_clock.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <mutex>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetTracker.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/ValueTransformer.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <openvdb/tree/LeafManager.h>
#include <stdexcept>
#include <system_error>

namespace sph {

// The union of the particles' spheres, smoothed, and the level where the
// fluid's surface is: -erosion (m), inside the spheres' union.
class LevelSet {
  public:
    LevelSet(openvdb::FloatGrid::Ptr grid, float isovalue)
        : grid_(std::move(grid)), isovalue_(isovalue) {}
    const openvdb::FloatGrid& grid() const { return *grid_; }
    float isovalue() const { return isovalue_; }

  private:
    openvdb::FloatGrid::Ptr grid_;
    float isovalue_;
};

namespace {

// Registers OpenVDB's grid types, once, before any grid is made or written.
void initialise_openvdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

// The snapshot's positions as ParticlesToLevelSet reads them.
class ParticleList {
  public:
    using PosType = openvdb::Vec3R;
    explicit ParticleList(const Snapshot& frame) : frame_(frame) {}
    std::size_t size() const { return frame_.size(); }
    void getPos(std::size_t n, openvdb::Vec3R& xyz) const {
        const Real* p = frame_.position.data() + 3 * n;
        xyz = openvdb::Vec3R(p[0], p[1], p[2]);
    }

  private:
    const Snapshot& frame_;
};

// The union of spheres holds, inside the fluid, each sphere's own distance
// (no deeper than -radius), so every voxel within reach of a particle is
// active: at 100k particles in a block, 1.1M voxels against the 0.4M of the
// band around the surface, and the first filter pass would work on all of
// them. A voxel further than the band's half width (in voxels, along any
// axis) from every voxel outside the spheres lies deeper than the band: it
// is set inside and off, as the filter's first renormalisation would have
// set it: 40 ms at 100k particles, where the filter spent 250 ms more on
// those voxels (sphclip_bench_surface --parts).
void drop_deep_inside(openvdb::FloatGrid& grid, int half_width) {
    openvdb::MaskGrid near_outside;
    {
        auto accessor = near_outside.getAccessor();
        for (auto v = grid.cbeginValueOn(); v; ++v)
            if (*v > 0)
                accessor.setValueOn(v.getCoord());
    }
    openvdb::tools::dilateActiveValues(near_outside.tree(), half_width,
                                       openvdb::tools::NN_FACE_EDGE_VERTEX,
                                       openvdb::tools::IGNORE_TILES);
    const float inside = -grid.background();
    // A leaf at a time on each thread: setValueOff writes the leaf's mask,
    // which two threads must not share.
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
    leaves.foreach ([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        const auto* near = near_outside.tree().probeConstLeaf(leaf.origin());
        // No leaf there: the mask holds the region as one tile, on or off.
        const bool all_near = !near && near_outside.tree().isValueOn(leaf.origin());
        for (auto v = leaf.beginValueOn(); v; ++v)
            if (*v <= 0 && !all_near && !(near && near->isValueOn(v.pos()))) {
                v.setValue(inside);
                v.setValueOff();
            }
    });
    openvdb::tools::pruneLevelSet(grid.tree());
}

} // namespace

std::shared_ptr<const LevelSet> make_level_set(const Snapshot& frame, double spacing,
                                               const SurfaceSettings& settings,
                                               SurfaceSteps* steps) {
    initialise_openvdb();
    SurfaceSteps ignored;
    SurfaceSteps& took = steps ? *steps : ignored;
    auto step_start = Clock::now();
    const double voxel = settings.voxel * spacing;
    const double radius = settings.radius * spacing;
    // Eroded back to where the drawn spheres' surface would be (radius
    // spacing / 2); the band must hold the erosion and a voxel beyond it,
    // the box filter's reach. Two voxels at the defaults (one of erosion):
    // the surface within 0.01 spacings (mean; 0.11 at most) of the one a
    // band of three gives, with a third fewer voxels to filter.
    const double erosion = std::max(0.0, radius - 0.5 * spacing);
    const float half_width = float(std::max(2.0, std::ceil(erosion / voxel) + 1));
    openvdb::FloatGrid::Ptr grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, half_width);
    grid->setName("surface");
    if (frame.size() > 0) {
        openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
        raster.rasterizeSpheres(ParticleList(frame), radius);
        raster.finalize(/*prune=*/true);
        drop_deep_inside(*grid, int(half_width));
        took.rasterise = seconds_since(step_start);
        step_start = Clock::now();
        openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*grid);
        // After each of a Gaussian pass's four box filters the tracker
        // renormalises the band (three sweeps); first-order upwind gradients
        // in place of the default fifth-order WENO make the whole
        // reconstruction 2.5-2.8x faster at 100k particles with the same
        // surface to the eye (sphclip_bench_surface, docs/rendering.md).
        // Fewer sweeps are faster still but leave the band short of a signed
        // distance, and the mesh at -erosion shrinks (8% fewer vertices).
        filter.setSpatialScheme(openvdb::math::FIRST_BIAS);
        for (int pass = 0; pass < settings.smoothing; ++pass)
            filter.gaussian(1);
        // The union's values inside are each sphere's own distance, not the
        // union's: a level below zero there holds pockets between the
        // particles. The filter's passes renormalise it into a signed
        // distance; without them the erosion is done by the filter here.
        if (settings.smoothing == 0 && erosion > 0) {
            filter.offset(float(erosion));
            took.smoothing = seconds_since(step_start);
            return std::make_shared<const LevelSet>(std::move(grid), 0.f);
        }
        took.smoothing = seconds_since(step_start);
    }
    // The erosion is not applied to the grid (LevelSetFilter::offset tracks
    // the band in small steps, and cost more than all the rest on the
    // benchmark): the mesh is taken at the level -erosion of the signed
    // distance instead, the same surface; the .vdb export applies it.
    return std::make_shared<const LevelSet>(std::move(grid), -float(erosion));
}

SurfaceMesh mesh_level_set(const LevelSet& level_set, SurfaceSteps* steps) {
    const auto start = Clock::now();
    const openvdb::FloatGrid& grid = level_set.grid();
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(grid, points, triangles, quads, level_set.isovalue(), 0.0);
    SurfaceMesh mesh;
    mesh.dimension = 3;
    const std::size_t nv = points.size();
    mesh.positions.resize(3 * nv);
    mesh.normals.resize(3 * nv);
    mesh.scalar.assign(nv, 0.f);
    mesh.triangles.reserve(3 * (triangles.size() + 2 * quads.size()));
    for (const openvdb::Vec3I& t : triangles)
        for (int k = 0; k < 3; ++k)
            mesh.triangles.push_back(t[k]);
    for (const openvdb::Vec4I& q : quads)
        for (int k : {0, 1, 2, 0, 2, 3})
            mesh.triangles.push_back(q[k]);
    // Normals from the level set's gradient (central differences of the
    // trilinearly interpolated distance), smooth across triangles and
    // pointing out of the fluid whatever the faces' winding.
    const double h = 0.5 * grid.voxelSize()[0];
    const auto normals_start = Clock::now();
#pragma omp parallel
    {
        openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
        openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
            sampler(accessor, grid.transform());
#pragma omp for schedule(static)
        for (std::size_t v = 0; v < nv; ++v) {
            const openvdb::Vec3R p(points[v]);
            openvdb::Vec3R g;
            for (int a = 0; a < 3; ++a) {
                openvdb::Vec3R d(0, 0, 0);
                d[a] = h;
                g[a] = sampler.wsSample(p + d) - sampler.wsSample(p - d);
            }
            const double length = g.length();
            if (length > 0)
                g /= length;
            else
                g = openvdb::Vec3R(0, 1, 0);
            for (int a = 0; a < 3; ++a) {
                mesh.positions[3 * v + a] = points[v][a];
                mesh.normals[3 * v + a] = float(g[a]);
            }
        }
    }
    if (steps) {
        steps->meshing = std::chrono::duration<double>(normals_start - start).count();
        steps->normals = seconds_since(normals_start);
    }
    return mesh;
}

void write_level_set(const LevelSet& level_set, const std::filesystem::path& path) {
    initialise_openvdb();
    std::filesystem::path temporary = path;
    temporary += ".partial";
    try {
        // The surface at zero, as a level set's reader expects, in a band of
        // OpenVDB's usual half width: the band widened by renormalisation,
        // then every distance shifted by the isovalue (so the zero level is
        // the meshed one, exactly), then trimmed to the half width.
        openvdb::FloatGrid::Ptr grid = level_set.grid().deepCopy();
        const float voxel = float(grid->voxelSize()[0]);
        const float shift = -level_set.isovalue();
        const int half_width = int(openvdb::LEVEL_SET_HALF_WIDTH);
        openvdb::tools::LevelSetTracker<openvdb::FloatGrid> tracker(*grid);
        tracker.setSpatialScheme(openvdb::math::FIRST_BIAS);
        tracker.resize(half_width + int(std::ceil(std::abs(shift) / voxel)));
        if (shift != 0) {
            openvdb::tools::foreach (
                grid->beginValueOn(),
                [&](const openvdb::FloatGrid::ValueOnIter& v) { v.setValue(*v + shift); });
            openvdb::tools::changeLevelSetBackground(grid->tree(), half_width * voxel);
            tracker.prune();
        }
        openvdb::io::File file(temporary.string());
        openvdb::GridCPtrVec grids{grid};
        file.write(grids);
        file.close();
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw std::runtime_error("cannot write " + path.string() + ": " + e.what());
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw std::runtime_error("cannot write " + path.string());
    }
}

} // namespace sph

extern "C" __attribute__((visibility("default"))) const sph::LevelSetFunctions*
sphclip_level_set_functions() {
    static constexpr sph::LevelSetFunctions functions{&sph::make_level_set, &sph::mesh_level_set,
                                                      &sph::write_level_set};
    return &functions;
}
