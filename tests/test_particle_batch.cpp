// Particle batching (src/render/particle_batch.*), without a GL context:
// which particles become instances, in which group, with which values.
#include "render/particle_batch.hpp"

#include <catch2/catch.hpp>

using namespace sph;

namespace {

// Three particles in a 3D domain [0, 1]^3, seen from in front: one at the
// centre, one far outside the view, one buried.
Snapshot three_particles() {
    Snapshot s;
    s.dimension = 3;
    s.position = {0.5, 0.5, 0.5, 50, 0.5, 0.5, 0.4, 0.5, 0.5};
    s.velocity = {3, 4, 0, 0, 0, 0, 1, 0, 0};
    s.density = {1000, 1001, 1002};
    s.pressure = {1, 2, 3};
    s.buried = {0, 0, 1};
    return s;
}

RenderSettings front_view() {
    RenderSettings r;
    r.width = 320;
    r.height = 180;
    r.dimension = 3;
    r.shadows = false; // with shadows nothing is culled outside the view
    r.radius = 0.01;
    r.camera_position = {0.5, 0.5, 3};
    r.camera_target = {0.5, 0.5, 0.5};
    return r;
}

} // namespace

TEST_CASE("the batch skips buried and unseen particles, and keeps the others' values", "[render]") {
    const Snapshot frame = three_particles();
    RenderSettings r = front_view();
    r.cull_buried = true;
    const Camera camera = make_camera(r, fixed_pose(r), layout_frame(r.width, r.height));
    ParticleBatch batch(r, outline_groups);
    batch.fill(frame, camera, OutlineRule(r));
    CHECK(batch.drawn() == 1);
    CHECK(batch.outside_view() == 1);
    // The centre particle, relative to the domain's centre, coloured by speed.
    const std::size_t group = batch.count(square_group) == 1 ? square_group : triangle_group;
    const auto instance = batch.instances(group);
    REQUIRE(instance.size() == 4);
    CHECK(instance[0] == 0.f);
    CHECK(instance[1] == 0.f);
    CHECK(instance[2] == 0.f);
    CHECK(instance[3] == 5.f);

    // Without culling, all three, in the snapshot's order.
    r.cull_buried = false;
    r.cull_outside_view = false;
    r.field = ColourField::density;
    ParticleBatch all(r, 1);
    all.fill(frame, camera, [](const SphereImage&) { return std::size_t(0); });
    CHECK(all.drawn() == 3);
    CHECK(all.outside_view() == 0);
    CHECK(all.instances(0)[3] == 1000.f);
    CHECK(all.instances(0)[7] == 1001.f);
    CHECK(all.instances(0)[11] == 1002.f);
}

TEST_CASE("the renderer's rule puts small impostors on triangles, meshes on squares", "[render]") {
    const Snapshot frame = three_particles();
    RenderSettings r = front_view();
    const Camera camera = make_camera(r, fixed_pose(r), layout_frame(r.width, r.height));
    // A 0.02 m sphere 2.5 m away is about a pixel across.
    for (SphereDrawing spheres : {SphereDrawing::impostor, SphereDrawing::mesh})
        for (double below : {0.0, 12.0}) {
            INFO(choice_name(spheres) << ", triangles below " << below << " px");
            r.spheres = spheres;
            r.triangles_below_px = below;
            ParticleBatch batch(r, outline_groups);
            batch.fill(frame, camera, OutlineRule(r));
            const bool triangles = r.spheres == SphereDrawing::impostor && below > 0;
            CHECK(batch.count(triangle_group) == (triangles ? 2u : 0u));
            CHECK(batch.count(square_group) == (triangles ? 0u : 2u));
        }
}
