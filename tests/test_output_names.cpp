// One name per quantity across the files sphclip writes (docs/outputs.md,
// "One name per quantity"): the headers of stats.csv, the particle exports,
// validate's and study's tables and JSON, read from small real runs, carry
// stats.csv's name for each quantity they share with it.

#include "support/run_sphclip.hpp"
#include "support/small_tank.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::read_text_csv;
using sph::test::run_sphclip;
using sph::test::TempFolder;
using sph::test::TextCsv;
using sph::test::write_text;

// 36 particles, 3 frames.
const std::string small_scene = sph::test::small_tank(0.05);

void require_ok(const sph::test::ProgramResult& result) {
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
}

double number(const std::string& cell) {
    return std::stod(cell);
}

} // namespace

TEST_CASE("the same quantity has the same name in every file sphclip writes",
          "[cli][outputs][validate][study]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    require_ok(run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out",
                                 (tmp / "run").string(), "--no-png", "--no-mp4", "--export", "csv",
                                 "--export", "vtk-ascii", "--quiet"}));
    require_ok(
        run_sphclip(tmp,
                    {"validate", "hydrostatic_2d", "dam_break_2d", "--out", (tmp / "v").string(),
                     "--set", "fluid.spacing=0.005", "--set", "duration=0.2", "--jobs", "2"},
                    SPHCLIP_SOURCE_DIR));
    require_ok(run_sphclip(tmp,
                           {"validate", "honey_spread_2d", "--out", (tmp / "h").string(), "--set",
                            "fluid.spacing=0.005", "--set", "duration=1.2"},
                           SPHCLIP_SOURCE_DIR));
    require_ok(
        run_sphclip(tmp,
                    {"study", "scenes/dam_break_2d.json", "--duration", "0.1", "--vary",
                     "fluid.spacing=0.004,0.006", "--jobs", "2", "--out", (tmp / "s").string()},
                    SPHCLIP_SOURCE_DIR));

    const TextCsv stats = read_text_csv(tmp / "run" / "stats.csv");
    const TextCsv particles = read_text_csv(tmp / "run" / "particles" / "frame_00001.csv");
    const std::string vtk = read_text(tmp / "run" / "particles" / "frame_00001.vtp");
    const TextCsv summary = read_text_csv(tmp / "v" / "summary.csv");
    const TextCsv surge = read_text_csv(tmp / "v" / "dam_break_2d" / "surge_front.csv");
    const TextCsv spreading = read_text_csv(tmp / "h" / "honey_spread_2d" / "spreading_front.csv");
    const TextCsv study = read_text_csv(tmp / "s" / "study.csv");
    const json metrics = json::parse(read_text(tmp / "v" / "hydrostatic_2d" / "metrics.json"));
    const json run = json::parse(read_text(tmp / "run" / "run.json"));

    struct Shared {
        std::string name;                  // stats.csv's name, or the exports' own
        std::vector<const TextCsv*> files; // the tables that must use it
    };
    const std::vector<Shared> shared = {
        {"frame", {&stats, &surge, &spreading}},
        {"time", {&stats, &particles, &surge, &spreading}},
        {"steps", {&stats, &summary, &study}},
        {"particles", {&stats, &summary, &study}},
        {"wall_s", {&stats, &summary, &study}},
        {"max_speed", {&stats, &summary}},
        {"density_error_avg_pct", {&stats, &summary, &study}},
        {"density_error_max_pct", {&stats, &study}},
        {"density", {&particles}},
        {"pressure", {&particles}},
        {"id", {&particles}},
    };
    for (const auto& quantity : shared)
        for (const TextCsv* file : quantity.files) {
            INFO(quantity.name << " in a header of " << file->header.size() << " columns");
            CHECK(file->has(quantity.name));
        }
    // VTK's arrays and the JSON files.
    for (const char* name : {"density", "pressure", "id"})
        CHECK(vtk.find(fmt::format("Name=\"{}\"", name)) != std::string::npos);
    CHECK(metrics.contains("max_speed"));
    CHECK(metrics.contains("density_error_avg_pct"));
    CHECK(run.contains("wall_s"));
    CHECK(run.contains("steps"));
    CHECK(run.contains("particles"));

    // The aligned columns hold the same numbers as the documented ones they
    // repeat, and the same times as stats.csv.
    REQUIRE(summary.rows.size() == 2);
    std::size_t hydrostatic = summary.at(0, "case") == "hydrostatic_2d" ? 0 : 1;
    CHECK(summary.at(hydrostatic, "max_speed") == summary.at(hydrostatic, "speed_max_m_s"));
    CHECK(!summary.at(hydrostatic, "max_speed").empty());
    CHECK(metrics.at("max_speed") == metrics.at("speed_max_m_s"));
    const TextCsv dam_stats = read_text_csv(tmp / "v" / "dam_break_2d" / "run" / "stats.csv");
    REQUIRE(!surge.rows.empty());
    for (std::size_t k = 0; k < surge.rows.size(); ++k) {
        const auto frame = std::stoul(surge.at(k, "frame"));
        CHECK(number(surge.at(k, "time")) == Approx(number(dam_stats.at(frame, "time"))));
        CHECK(number(surge.at(k, "time")) == Approx(number(surge.at(k, "time_s"))));
    }
    REQUIRE(!spreading.rows.empty());
    for (std::size_t k = 0; k < spreading.rows.size(); ++k)
        CHECK(number(spreading.at(k, "time")) == Approx(number(spreading.at(k, "time_s"))));
    CHECK(number(particles.at(0, "time")) == Approx(number(stats.at(1, "time"))));
}
