// Render benchmark: milliseconds per 1280x720 frame by backend, sphere
// technique, particle count and layout (a fluid block, or scattered
// particles). A program that prints a table, not a timed test.
//
//   build/sphclip_bench_render                 # the full table
//   build/sphclip_bench_render --tiny          # one small frame per case (CI)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "sph/neighbours/spatial_hash.hpp"
#include "sph/surface.hpp"

using namespace sph;

namespace {

// n particles: a cube of fluid on a lattice, or uniformly scattered in the
// same box, with speeds that vary so the colour map is exercised.
Snapshot make_particles(std::size_t n, bool block, double spacing, double box) {
    Snapshot s;
    s.dimension = 3;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    const std::size_t side = std::size_t(std::ceil(std::cbrt(double(n))));
    for (std::size_t i = 0; i < n; ++i) {
        double x, y, z;
        if (block) {
            x = (double(i % side) + 0.5) * spacing;
            y = (double(i / side % side) + 0.5) * spacing;
            z = (double(i / side / side) + 0.5) * spacing;
        } else {
            x = u(rng) * box;
            y = u(rng) * box;
            z = u(rng) * box;
        }
        s.position.insert(s.position.end(), {x, y, z});
        s.velocity.insert(s.velocity.end(), {2 * y / box, 0, 0});
        s.density.push_back(1000);
        s.pressure.push_back(0);
        s.id.push_back(std::uint32_t(i));
    }
    return s;
}

double median_ms(FrameRenderer& renderer, const Snapshot& s, int repeat) {
    std::vector<double> ms;
    for (int r = 0; r < repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        renderer.render(s);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    const bool tiny = argc > 1 && std::strcmp(argv[1], "--tiny") == 0;
    const std::vector<std::size_t> counts =
        tiny ? std::vector<std::size_t>{1000} : std::vector<std::size_t>{10000, 100000};
    const int width = tiny ? 320 : 1280, height = tiny ? 180 : 720, repeat = tiny ? 1 : 5;
    fmt::print("backend,spheres,skip_buried,layout,particles,drawn,width,height,ms_per_frame,"
               "draw_ms,readback_ms\n");
    for (const char* backend : {"egl", "osmesa"}) {
        auto context = make_gl_context(backend);
        // (technique, skip buried): the last is the seed's way, every mesh drawn.
        const std::pair<const char*, bool> techniques[] = {
            {"impostor", true}, {"mesh", true}, {"mesh", false}};
        for (const auto& [spheres, skip_buried] : techniques) {
            for (bool block : {true, false}) {
                if (!block && !skip_buried)
                    continue; // scattered particles have none buried
                for (std::size_t n : counts) {
                    // The block's spheres are ~8 px across at 100k, as a fluid
                    // fills the frame in a clip.
                    const double side = std::ceil(std::cbrt(double(n)));
                    const double spacing = 0.1 / side, box = 0.1;
                    RenderSettings settings;
                    settings.width = width;
                    settings.height = height;
                    settings.dimension = 3;
                    settings.spheres = spheres;
                    settings.radius = 0.5 * spacing;
                    settings.range = {0, 2};
                    settings.domain_min = glm::dvec3(0);
                    settings.domain_max = glm::dvec3(box);
                    settings.camera_target = glm::dvec3(0.05);
                    settings.camera_position = glm::dvec3(0.05) + 0.2 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
                    Snapshot s = make_particles(n, block, spacing, box);
                    // As in a run: neighbour counts let buried particles be skipped
                    // (for the fluid block; scattered particles are a gas, all visible).
                    const double h = 2.2 * spacing;
                    settings.cull_buried = block && skip_buried;
                    State<3> state;
                    state.resize(n);
                    for (std::size_t i = 0; i < n; ++i)
                        state.position[i] = {s.position[3 * i], s.position[3 * i + 1],
                                             s.position[3 * i + 2]};
                    NeighbourList list;
                    SpatialHash<3>().find(state.position, h, list);
                    mark_buried(state, list, spacing, s.buried);
                    FrameRenderer renderer(settings);
                    renderer.render(s); // warm-up: shader compilation, buffers
                    const double ms = median_ms(renderer, s, repeat);
                    fmt::print("{},{},{},{},{},{},{},{},{:.1f},{:.1f},{:.1f}\n", backend,
                               spheres, skip_buried ? "yes" : "no", block ? "block" : "scattered", n, renderer.last_drawn(), width,
                               height, ms,
                               renderer.last_timings().draw_seconds * 1e3,
                               renderer.last_timings().readback_seconds * 1e3);
                    std::fflush(stdout);
                }
            }
        }
    }
    return 0;
}
