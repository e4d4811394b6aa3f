#include "cli/build_info.hpp"

#include "sph/single_precision/single_passes.hpp"
#include "sph/vector_clones.hpp"
#include "sphclip_build_info.hpp"

#include <ctime>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <thread>

namespace sph {

std::string build_git_commit() {
    return SPHCLIP_BUILD_GIT_COMMIT;
}

std::vector<std::string> built_instruction_sets() {
    std::vector<std::string> sets;
    // The compiler defines one macro per extension that -march lets it use;
    // this file is compiled with the same flags as the simulation.
#ifdef __SSE2__
    sets.push_back("sse2");
#endif
#ifdef __SSE4_2__
    sets.push_back("sse4.2");
#endif
#ifdef __AVX__
    sets.push_back("avx");
#endif
#ifdef __AVX2__
    sets.push_back("avx2");
#endif
#ifdef __FMA__
    sets.push_back("fma");
#endif
#ifdef __AVX512F__
    sets.push_back("avx512f");
#endif
#ifdef __AVX512DQ__
    sets.push_back("avx512dq");
#endif
#ifdef __AVX512BW__
    sets.push_back("avx512bw");
#endif
#ifdef __AVX512VL__
    sets.push_back("avx512vl");
#endif
#ifdef __ARM_NEON
    sets.push_back("neon");
#endif
#ifdef __ARM_FEATURE_SVE
    sets.push_back("sve");
#endif
    return sets;
}

nlohmann::json build_json() {
    return {{"git_commit", SPHCLIP_BUILD_GIT_COMMIT},
            {"compiler",
             fmt::format("{} {}", SPHCLIP_BUILD_COMPILER_ID, SPHCLIP_BUILD_COMPILER_VERSION)},
            {"build_type", SPHCLIP_BUILD_TYPE},
            {"flags", SPHCLIP_BUILD_FLAGS},
            {"arch", SPHCLIP_BUILD_ARCH},
            {"instruction_sets", built_instruction_sets()},
            {"simd_variants",
             std::vector<std::string>(simd_variants().begin(), simd_variants().end())}};
}

std::string cpu_model(const std::string& cpuinfo_text) {
    std::istringstream lines(cpuinfo_text);
    std::string line;
    std::string fallback;
    while (std::getline(lines, line)) {
        const auto colon = line.find(':');
        if (colon == std::string::npos)
            continue;
        std::string key = line.substr(0, colon);
        while (!key.empty() && (key.back() == ' ' || key.back() == '\t'))
            key.pop_back();
        const auto start = line.find_first_not_of(" \t", colon + 1);
        const std::string value = start == std::string::npos ? "" : line.substr(start);
        if (value.empty())
            continue;
        if (key == "model name")
            return value;
        if (fallback.empty() && (key == "Model" || key == "Hardware"))
            fallback = value;
    }
    return fallback.empty() ? "unknown" : fallback;
}

nlohmann::json machine_json() {
    std::ifstream in("/proc/cpuinfo");
    std::stringstream text;
    if (in)
        text << in.rdbuf();
    // The single-precision passes' variant on this processor (SPHCLIP_SIMD
    // was checked before the run started).
    std::string variant;
    try {
        variant = simd_variant();
    } catch (const std::exception&) {
        variant = "unknown";
    }
    return {{"cpu_model", cpu_model(text.str())},
            {"logical_cpus", std::thread::hardware_concurrency()},
            {"simd_variant", variant},
            // The double-precision passes' (sph/vector_clones.hpp).
            {"double_variant", vector_clone_variant()}};
}

std::string utc_iso8601(std::chrono::system_clock::time_point time) {
    const std::time_t seconds = std::chrono::system_clock::to_time_t(time);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

} // namespace sph
