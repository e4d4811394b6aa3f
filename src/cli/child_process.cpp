#include "cli/child_process.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <spawn.h>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace sph {

namespace fs = std::filesystem;

fs::path self_executable() {
    const fs::path program = fs::read_symlink("/proc/self/exe");
    // Started through the launcher (cli/launcher.c): the launcher is what
    // users and scripts call, and the data lies beside it. Taken only when
    // its program proper is this very file, so that a variable inherited
    // from another build's launcher is not.
    if (const char* launcher = std::getenv("SPHCLIP_LAUNCHER"); launcher && *launcher) {
        const fs::path folder = fs::path(launcher).parent_path();
        for (const char* place : {SPHCLIP_PROGRAM_INSTALLED, SPHCLIP_PROGRAM_IN_BUILD}) {
            std::error_code ec;
            if (fs::equivalent(folder / place, program, ec))
                return launcher;
        }
    }
    return program;
}

pid_t start_child(const std::string& program, const std::vector<std::string>& argv,
                  const fs::path& log, bool search_path, const fs::path& cwd) {
    std::vector<char*> args;
    for (const auto& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    if (!cwd.empty())
        posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    pid_t pid = 0;
    const int error =
        search_path ? posix_spawnp(&pid, program.c_str(), &actions, nullptr, args.data(), environ)
                    : posix_spawn(&pid, program.c_str(), &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0)
        throw std::runtime_error(fmt::format("cannot start {}: {}", program, std::strerror(error)));
    return pid;
}

std::optional<int> child_exit_code(pid_t pid, bool wait) {
    int status = 0;
    pid_t done;
    do {
        done = waitpid(pid, &status, wait ? 0 : WNOHANG);
    } while (done < 0 && errno == EINTR);
    if (done == 0)
        return std::nullopt;
    if (done < 0)
        return -1;
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    return 128 + WTERMSIG(status);
}

std::string last_lines(const fs::path& file, std::size_t count) {
    std::ifstream in(file);
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line))
        if (!line.empty())
            lines.push_back(line);
    std::string text;
    for (std::size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i)
        text += (text.empty() ? "" : "\n") + lines[i];
    return text;
}

std::string error_line(const fs::path& log) {
    std::ifstream in(log);
    std::string line, last, error;
    while (std::getline(in, line)) {
        if (line.empty())
            continue;
        last = line;
        if (line.find("error:") != std::string::npos)
            error = line;
    }
    return error.empty() ? last : error;
}

} // namespace sph
