// Hostile inputs the fuzzers found (tests/fuzz/run_fuzzer.sh) and hand-made
// ones, read by the normal build: scene files (tests/fuzz/regressions/), OBJ
// meshes and PNG images (tests/fuzz/regressions/{obj,png}/ and the committed
// corpora tests/fuzz/corpus/{obj,png}/). Each must load, or be refused with
// the reader's own error naming the file.

#include "output/png_io.hpp"
#include "scene/input_error.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene.hpp"
#include "support/temp_folder.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

TEST_CASE("every fuzz regression input loads or is refused as bad input", "[scene][fuzz]") {
    std::vector<fs::path> inputs;
    for (const auto& entry : fs::directory_iterator(SPHCLIP_FUZZ_REGRESSIONS_DIR))
        if (entry.is_regular_file())
            inputs.push_back(entry.path());
    std::sort(inputs.begin(), inputs.end());
    REQUIRE(inputs.size() >= 5);

    for (const auto& input : inputs) {
        const std::string label = input.filename().string();
        INFO(label);
        const std::string text = sph::test::read_text(input);
        try {
            const sph::Scene scene = sph::parse_scene(text, label, {});
            const sph::Derived derived = sph::derive(scene);
            CHECK(derived.particles > 0);
        } catch (const sph::InputError& e) {
            CHECK(e.file == label);
            CHECK(std::string(e.what()).starts_with(label + ": "));
        } catch (const std::exception& e) {
            FAIL_CHECK("not an InputError: " << e.what());
        }
    }
}

namespace {

// The regular files in the folders below tests/fuzz/ named by `folders`.
std::vector<fs::path> fuzz_inputs(const std::vector<std::string>& folders) {
    const fs::path fuzz = fs::path(SPHCLIP_FUZZ_REGRESSIONS_DIR).parent_path();
    std::vector<fs::path> inputs;
    for (const auto& folder : folders)
        if (fs::is_directory(fuzz / folder))
            for (const auto& entry : fs::directory_iterator(fuzz / folder))
                if (entry.is_regular_file())
                    inputs.push_back(entry.path());
    std::sort(inputs.begin(), inputs.end());
    return inputs;
}

} // namespace

TEST_CASE("every OBJ fuzz input loads as a solid or is refused as bad input", "[mesh][fuzz]") {
    const auto inputs = fuzz_inputs({"corpus/obj", "regressions/obj"});
    REQUIRE(inputs.size() >= 4);
    std::size_t solids = 0;
    for (const auto& input : inputs) {
        INFO(input.string());
        try {
            const auto mesh = sph::read_obj_mesh(input, 1, sph::Vec<3>(0), "fuzz.json", "mesh");
            CHECK_FALSE(mesh->triangles().empty());
            ++solids;
        } catch (const sph::InputError& e) {
            CHECK(e.file == "fuzz.json");
            CHECK(e.field == "mesh");
            CHECK(std::string(e.problem).find(input.string()) != std::string::npos);
        } catch (const std::exception& e) {
            FAIL_CHECK("not an InputError: " << e.what());
        }
    }
    CHECK(solids >= 3); // the corpus's tetrahedra and cube
}

TEST_CASE("every PNG fuzz input decodes or is refused as unreadable", "[png][fuzz]") {
    const auto inputs = fuzz_inputs({"corpus/png", "regressions/png"});
    REQUIRE(inputs.size() >= 7);
    std::size_t images = 0;
    for (const auto& input : inputs) {
        INFO(input.string());
        try {
            const sph::Image image = sph::read_png(input);
            CHECK(image.rgba.size() == std::size_t(image.width) * std::size_t(image.height) * 4);
            ++images;
        } catch (const sph::ImageReadError& e) {
            CHECK(e.path == input);
        } catch (const std::exception& e) {
            FAIL_CHECK("not an ImageReadError: " << e.what());
        }
    }
    CHECK(images >= 7); // the corpus's colour types
}
