#pragma once
// What run.json records so that a run can be reproduced: how this binary was
// built (taken when CMake configured: cmake/build_info.cmake), the machine
// it runs on, and wall-clock times in UTC.

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sph {

// run.json "build": git_commit ("unknown" outside git), compiler, build_type,
// flags, arch (-march; empty: the compiler's default), instruction_sets.
nlohmann::json build_json();
// This build's git commit, as build_json() has it.
std::string build_git_commit();
// The instruction-set extensions the compiler was allowed to use, from its
// predefined macros (-march): "sse2", "avx2", "avx512f", ...
std::vector<std::string> built_instruction_sets();

// run.json "machine": cpu_model (from /proc/cpuinfo, "unknown" without it)
// and logical_cpus.
nlohmann::json machine_json();
// /proc/cpuinfo's first "model name" (x86) or "Model"/"Hardware" (Arm);
// "unknown" when there is none.
std::string cpu_model(const std::string& cpuinfo_text);

// ISO 8601 in UTC to the second: "2026-12-02T01:23:45Z".
std::string utc_iso8601(std::chrono::system_clock::time_point time);

} // namespace sph
