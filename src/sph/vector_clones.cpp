#include "sph/vector_clones.hpp"

namespace sph {

const char* vector_clone_variant() {
#ifdef SPHCLIP_VECTOR_CLONES_ON
    // The resolvers' own test, in their order (widest first).
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4"))
        return "x86-64-v4";
    if (__builtin_cpu_supports("x86-64-v3"))
        return "x86-64-v3";
    return "baseline";
#elif defined(SPHCLIP_VECTOR_CLONES)
    return "baseline"; // a portable build by a compiler without the clones (clang)
#else
    return "native";
#endif
}

} // namespace sph
