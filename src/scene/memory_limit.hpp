#pragma once
// How much memory a run may use: the least of the machine's RAM, the
// process's address-space limit (RLIMIT_AS, `ulimit -v`) less what it already
// maps, and its cgroup's limit (v2 memory.max, v1 memory.limit_in_bytes), as
// a container or a systemd unit sets it. A scene that needs more is refused
// before anything is written (docs/contract.md, "Memory").

#include <filesystem>
#include <optional>
#include <string>

namespace sph {

struct MemoryLimit {
    double bytes = 0; // 0: unknown, no check
    std::string what; // for messages: "this machine has 23.4 GiB"
};

// The tightest of the limits that apply to this process.
MemoryLimit memory_limit();

// The cgroup memory limit for a process whose /proc/self/cgroup reads
// `proc_self_cgroup`, with the cgroup filesystem mounted at `cgroup_root`
// (/sys/fs/cgroup); the tightest over the cgroup and its parents. None when
// no limit is set or none can be read.
std::optional<MemoryLimit> cgroup_memory_limit(const std::string& proc_self_cgroup,
                                               const std::filesystem::path& cgroup_root);

} // namespace sph
