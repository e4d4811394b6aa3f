#pragma once
// Libraries loaded when a run first needs them, not when the program starts.
// Linked the usual way, FFmpeg (with its 130 codec libraries), OSMesa (with
// LLVM) and OpenVDB cost every start about 0.2 s in the dynamic loader's
// relocations, measured with `perf record` on `sphclip --version`: more than
// a short run's simulation, paid again by every child of `validate` and
// `study` and by runs that write neither PNG nor MP4. Loaded here by their
// soname, they cost that only in the runs that use them.
//
// A library stays loaded until the program ends (LLVM and OpenVDB keep state
// that outlives a dlclose).

#include <string>

namespace sph {

// The library `soname` (dlopen with RTLD_NOW: a missing symbol is found
// here, not in the middle of a run); loaded once, then the same handle.
// Throws std::runtime_error naming the library and the loader's reason.
void* shared_library(const std::string& soname);

// The address of `name` in a library from shared_library(). Throws
// std::runtime_error naming both.
void* library_symbol(void* library, const std::string& soname, const char* name);

// `name` from `soname`, as a pointer of the type of the function it was
// declared as in the library's header (Function = decltype(&name)).
template <class Function>
Function library_function(const std::string& soname, const char* name) {
    return reinterpret_cast<Function>(library_symbol(shared_library(soname), soname, name));
}

} // namespace sph
