#pragma once
// Runs the real program as a child with one resource limit set (setrlimit
// in the child, before the exec), its stdout and stderr in a log: how the
// contract tests make a full disk (RLIMIT_FSIZE) or a small address space
// (RLIMIT_AS) without root.

#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace sph::test {

struct LimitedRun {
    int exit_code = -1; // 128 + signal when killed
    std::string output;
};

// `sphclip ARGS...` with `resource` limited to `max_bytes`. SIGXFSZ is put
// back to its default (kill) in the child, so a run that did not ignore it
// would die rather than see the write fail.
inline LimitedRun run_with_limit(const TempFolder& tmp, const std::vector<std::string>& args,
                                 int resource, rlim_t max_bytes) {
    const std::filesystem::path log = tmp / "sphclip.log";
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(log_fd, STDOUT_FILENO);
        dup2(log_fd, STDERR_FILENO);
        signal(SIGXFSZ, SIG_DFL);
        const rlimit limit{max_bytes, max_bytes};
        setrlimit(resource, &limit);
        setenv("OMP_WAIT_POLICY", "passive", 1);
        std::vector<char*> argv{const_cast<char*>(SPHCLIP_EXE)};
        for (const auto& a : args)
            argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(SPHCLIP_EXE, argv.data());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    LimitedRun result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.output = read_text(log);
    return result;
}

} // namespace sph::test
