// SPHCLIP_ASSERT (src/sph/assert.hpp) is on in every build but Release, and
// in the sanitizer builds, and a failed one stops the program with the
// expression and where it is.
#include "sph/assert.hpp"

#include <catch2/catch.hpp>
#include <csignal>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

// Runs `body` in a child process; its exit status and what it wrote to stderr.
template <class Body>
std::pair<int, std::string> in_child(Body body) {
    int pipe_fds[2];
    REQUIRE(pipe(pipe_fds) == 0);
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        close(pipe_fds[0]);
        dup2(pipe_fds[1], STDERR_FILENO);
        body();
        _exit(0);
    }
    close(pipe_fds[1]);
    std::string text;
    char buffer[512];
    for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
        text.append(buffer, static_cast<std::size_t>(n));
    close(pipe_fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return {status, text};
}

} // namespace

TEST_CASE("SPHCLIP_ASSERT is on outside Release builds and under the sanitizers", "[assert]") {
    const std::string build_type = SPHCLIP_BUILD_TYPE;
    bool expected = build_type != "Release" && build_type != "MinSizeRel";
#if defined(__SANITIZE_ADDRESS__)
    expected = true;
#endif
    CHECK(sph::asserts_enabled == expected);
}

TEST_CASE("a failed SPHCLIP_ASSERT aborts and names the expression", "[assert]") {
    const auto [status, text] = in_child([] {
        volatile int particles = 3;
        SPHCLIP_ASSERT(particles == 4);
    });
    if (sph::asserts_enabled) {
        REQUIRE(WIFSIGNALED(status));
        CHECK(WTERMSIG(status) == SIGABRT);
        CHECK(text.find("assertion failed: particles == 4") != std::string::npos);
        CHECK(text.find("test_assert.cpp") != std::string::npos);
    } else {
        // Off: the expression is not evaluated and the child exits normally.
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) == 0);
    }
}
