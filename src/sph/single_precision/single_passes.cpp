#include "sph/single_precision/single_passes.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace sph {

// The variants' factories (cell_passes_*.cpp): which exist is the build's
// choice (src/CMakeLists.txt, SPHCLIP_SIMD_DISPATCH).
#ifdef SPHCLIP_SIMD_DISPATCH
namespace avx512 {
template <int D>
std::unique_ptr<SinglePasses<D>> make_passes();
}
namespace avx2 {
template <int D>
std::unique_ptr<SinglePasses<D>> make_passes();
}
#endif
namespace baseline {
template <int D>
std::unique_ptr<SinglePasses<D>> make_passes();
}

namespace {

#ifdef SPHCLIP_SIMD_DISPATCH
constexpr std::string_view variants[] = {"avx512", "avx2", "baseline"};
#else
constexpr std::string_view variants[] = {"native"};
#endif

} // namespace

std::span<const std::string_view> simd_variants() {
    return variants;
}

bool simd_variant_runs(std::string_view variant) {
#ifdef SPHCLIP_SIMD_DISPATCH
    __builtin_cpu_init();
    const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    if (variant == "avx512")
        return v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512cd");
    if (variant == "avx2")
        return v3;
#endif
    return std::find(std::begin(variants), std::end(variants), variant) != std::end(variants);
}

std::string_view simd_variant() {
    if (const char* asked = std::getenv("SPHCLIP_SIMD"); asked && *asked) {
        const std::string_view name = asked;
        const auto known = std::find(std::begin(variants), std::end(variants), name);
        if (known == std::end(variants)) {
            std::string names;
            for (const auto v : variants)
                names += (names.empty() ? "" : ", ") + std::string(v);
            throw std::runtime_error("SPHCLIP_SIMD=" + std::string(name) +
                                     ": this sphclip holds the variants " + names);
        }
        if (!simd_variant_runs(name))
            throw std::runtime_error("SPHCLIP_SIMD=" + std::string(name) +
                                     ": this processor cannot run that variant");
        return *known;
    }
    for (const auto v : variants)
        if (simd_variant_runs(v))
            return v;
    return variants[std::size(variants) - 1];
}

std::string_view simd_instructions() {
    const std::string_view variant = simd_variant();
    if (variant != "native" && variant != "baseline")
        return variant;
        // This file is compiled with the build's -march, as those variants are.
#if defined(__AVX512F__)
    return "avx512";
#elif defined(__AVX2__)
    return "avx2";
#else
    return "sse";
#endif
}

bool single_passes_pay() {
    const std::string_view variant = simd_variant();
    if (variant == "native") {
#ifdef __AVX2__
        return true;
#else
        return false;
#endif
    }
    return variant != "baseline";
}

template <int D>
std::unique_ptr<SinglePasses<D>> make_single_passes() {
    [[maybe_unused]] const std::string_view variant = simd_variant();
#ifdef SPHCLIP_SIMD_DISPATCH
    if (variant == "avx512")
        return avx512::make_passes<D>();
    if (variant == "avx2")
        return avx2::make_passes<D>();
#endif
    return baseline::make_passes<D>();
}

template std::unique_ptr<SinglePasses<2>> make_single_passes<2>();
template std::unique_ptr<SinglePasses<3>> make_single_passes<3>();

} // namespace sph
