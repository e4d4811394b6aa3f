// Hostile scene files (tests/fuzz/regressions/): inputs the scene fuzzer
// found (tests/fuzz/run_fuzzer.sh) and hand-made ones. Each must load, or be
// refused with an InputError naming the file, built with the normal compiler.

#include "io/input_error.hpp"
#include "io/scene.hpp"
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
