#include "analysis/run_outputs.hpp"

#include "analysis/csv_table.hpp"
#include "output/files.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sph {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

void read_stats(const fs::path& path, RunOutputs& out) {
    CsvTable stats;
    try {
        stats = read_csv_table(path);
    } catch (const std::exception&) {
        return;
    }
    if (stats.has("dt") && stats.rows() > 0) {
        double sum = 0;
        std::size_t count = 0;
        for (double dt : stats.column("dt"))
            if (std::isfinite(dt) && dt > 0) {
                sum += dt;
                ++count;
            }
        out.dt_avg = count ? sum / double(count) : nan;
    }
    if (stats.has("density_error_avg_pct") && stats.rows() > 1) {
        const auto& avg = stats.column("density_error_avg_pct");
        double sum = 0;
        for (std::size_t k = 1; k < avg.size(); ++k)
            sum += avg[k];
        out.density_error_avg_pct = sum / double(avg.size() - 1);
    }
    if (stats.has("density_error_max_pct") && stats.rows() > 0) {
        const auto& max = stats.column("density_error_max_pct");
        out.density_error_max_pct = *std::max_element(max.begin(), max.end());
    }
    if (out.particles == 0 && stats.has("particles") && stats.rows() > 0)
        out.particles = std::size_t(stats.column("particles").back());
}

std::vector<double> vector_at(const json& scene, const json::json_pointer& pointer) {
    if (!scene.contains(pointer) || !scene.at(pointer).is_array())
        throw std::runtime_error("run.json: scene has no " + pointer.to_string());
    return scene.at(pointer).get<std::vector<double>>();
}

double number_at(const json& scene, const json::json_pointer& pointer) {
    if (!scene.contains(pointer) || !scene.at(pointer).is_number())
        throw std::runtime_error("run.json: scene has no number at " + pointer.to_string());
    return scene.at(pointer).get<double>();
}

} // namespace

RunOutputs read_run_outputs(const fs::path& run) {
    RunOutputs out{"missing", 0, 0, nan, nan, nan, nan, json::object()};
    try {
        if (fs::exists(run / "run.json")) {
            const json doc = json::parse(read_input_file(run / "run.json", run_record_limit));
            out.status = doc.value("status", "missing");
            out.steps = doc.value("steps", std::uint64_t(0));
            out.particles = doc.value("particles", std::size_t(0));
            if (doc.contains("wall_s") && doc["wall_s"].is_number())
                out.wall_s = doc["wall_s"].get<double>();
            if (doc.contains("scene"))
                out.scene = doc["scene"];
        }
    } catch (const std::exception&) {
        out.status = "missing";
    }
    read_stats(run / "stats.csv", out);
    return out;
}

std::vector<double> frame_times(const fs::path& run) {
    const CsvTable stats = read_csv_table(run / "stats.csv");
    const auto& frame = stats.column("frame");
    const auto& time = stats.column("time");
    std::vector<double> times;
    for (std::size_t k = 0; k < stats.rows(); ++k) {
        if (!(frame[k] >= 0))
            continue;
        const auto f = std::size_t(frame[k]);
        if (times.size() <= f)
            times.resize(f + 1, nan);
        times[f] = time[k];
    }
    return times;
}

SceneFacts scene_facts(const json& scene) {
    SceneFacts facts;
    facts.dimension = int(number_at(scene, json::json_pointer("/dimension")));
    facts.spacing = number_at(scene, json::json_pointer("/fluid/spacing"));
    facts.rest_density = number_at(scene, json::json_pointer("/material/rest_density"));
    const json::json_pointer gravity("/effects/gravity");
    if (scene.contains(gravity) && scene.at(gravity).is_array()) {
        double g2 = 0;
        for (double g : scene.at(gravity).get<std::vector<double>>())
            g2 += g * g;
        facts.gravity = std::sqrt(g2);
    }
    const json::json_pointer mu("/effects/viscosity/mu");
    if (scene.contains(mu) && scene.at(mu).is_number())
        facts.viscosity = scene.at(mu).get<double>();
    facts.domain_min = vector_at(scene, json::json_pointer("/domain/min"));
    facts.domain_max = vector_at(scene, json::json_pointer("/domain/max"));
    facts.block_min = vector_at(scene, json::json_pointer("/fluid/blocks/0/min"));
    facts.block_max = vector_at(scene, json::json_pointer("/fluid/blocks/0/max"));
    return facts;
}

} // namespace sph
