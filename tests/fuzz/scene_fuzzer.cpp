// libFuzzer target for the scene parser (src/scene/scene.cpp): any text must
// either give a scene or an InputError. Another exception, a crash, undefined
// behaviour, a huge allocation or a hang is a finding. Built only with
// -DSPHCLIP_FUZZ=ON and clang; run with tests/fuzz/run_fuzzer.sh.

#include "scene/input_error.hpp"
#include "scene/scene.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    sph::Scene scene;
    sph::Derived derived;
    try {
        scene = sph::parse_scene(text, "fuzz input", {});
        derived = sph::derive(scene);
    } catch (const sph::InputError&) {
        return 0; // the expected answer to bad input
    }
    // A scene that loads must have finite derived values (the run would
    // otherwise turn NaN at its first step)...
    if (!std::isfinite(derived.h) || !std::isfinite(derived.mass) || !std::isfinite(derived.dt) ||
        !(derived.mass > 0) || !(derived.dt > 0)) {
        std::fprintf(stderr, "non-finite or zero derived value: h %g, mass %g, dt %g\n", derived.h,
                     derived.mass, derived.dt);
        std::abort();
    }
    // ...and its resolved form must load again: run.json is fed back as a scene.
    try {
        sph::parse_scene(sph::to_json(scene).dump(), "fuzz input, resolved", {});
    } catch (const sph::InputError& e) {
        std::fprintf(stderr, "the resolved scene does not load: %s\n", e.what());
        std::abort();
    }
    return 0;
}
