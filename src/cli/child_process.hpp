#pragma once
// Child processes for `validate` and `study` (each simulation is a separate
// `sphclip run`, so a crash or a blow-up in one cannot take the others down)
// and for gnuplot.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace sph {

// This program as users call it: its launcher (cli/launcher.c) when it was
// started through one, else its own file (/proc/self/exe). The folder the
// data is found from, and the program Slurm jobs and plans name.
std::filesystem::path self_executable();

// Starts `program` (looked up in PATH when `search_path`) with the arguments
// `argv` (argv[0] is its name in messages) in the folder `cwd` (empty: this
// one), with no input and its output and errors into `log`. Throws
// std::runtime_error when it cannot be started.
pid_t start_child(const std::string& program, const std::vector<std::string>& argv,
                  const std::filesystem::path& log, bool search_path,
                  const std::filesystem::path& cwd = {});

// The program for `start_child` that is this very program: /proc/self/exe as
// the child sees it, its parent's image, even when a rebuild has replaced
// the file since this program started.
inline constexpr const char* this_program = "/proc/self/exe";

// The child's exit code once it has ended (128 + the signal when a signal
// ended it); nullopt while it still runs, unless `wait`.
std::optional<int> child_exit_code(pid_t pid, bool wait);

// The last `count` non-empty lines of a text file, joined by newlines.
std::string last_lines(const std::filesystem::path& file, std::size_t count);

// The last line of a child's log that says "error:" (sphclip's messages do),
// else its last line: why a run stopped, in one line.
std::string error_line(const std::filesystem::path& log);

} // namespace sph
