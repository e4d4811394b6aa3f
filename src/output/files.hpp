#pragma once
// File writing that never leaves a half-written file behind, and reading
// that never reads without bound.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sph {

// A write that failed for want of room: the disk or the user's quota is full
// (ENOSPC, EDQUOT), or the file would pass the process's file-size limit
// (EFBIG, `ulimit -f`). A run that meets one stops and says what it kept
// (docs/contract.md, "A full disk").
struct OutOfSpaceError : std::runtime_error {
    std::filesystem::path path;
    int error; // the errno
    OutOfSpaceError(std::filesystem::path path_, int error_, const std::string& message)
        : std::runtime_error(message), path(std::move(path_)), error(error_) {}
};

// True for the errno values of OutOfSpaceError.
bool is_out_of_space(int error);

// Throws OutOfSpaceError when `error` is one, else std::runtime_error:
// "cannot write PATH: REASON".
[[noreturn]] void throw_write_error(const std::filesystem::path& path, int error);

// Writes to a temporary name beside `path`, then renames: readers see the old
// file or the whole new one. Throws OutOfSpaceError or std::runtime_error
// naming the path; the temporary is removed then.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

// Overwrites the existing regular file `path` from its first byte and cuts it
// to `content`'s length; `content` must fit in the file's present size.
// Rewriting bytes a file already holds and shrinking it need no free space
// where the filesystem overwrites in place (ext4, XFS, tmpfs; not the
// copy-on-write btrfs or ZFS), and no file grows, so `ulimit -f` is not met
// either: this works on a full disk, where write_file_atomically cannot. Not
// atomic: a reader may see a mix while it runs. Throws std::runtime_error.
void write_file_in_place(const std::filesystem::path& path, std::string_view content);

// The largest input of each kind that sphclip reads (docs: "Input limits").
// Far above any real file of the kind; what they stop is a device, a pipe or
// a runaway file read until memory runs out.
struct InputLimit {
    const char* kind;    // "scene file", "mesh file", "PNG image"
    std::uint64_t bytes; // at most
};
inline constexpr InputLimit scene_file_limit{"scene file", std::uint64_t(16) << 20};
inline constexpr InputLimit mesh_file_limit{"mesh file", std::uint64_t(512) << 20};
inline constexpr InputLimit png_file_limit{"PNG image", std::uint64_t(256) << 20};
// A run's record, read back by a re-run (`sphclip run out/x/run.json`), by
// the next run into its folder and by collect.
inline constexpr InputLimit run_record_limit{"run.json", std::uint64_t(64) << 20};
// A plan's files (plan.json, plan/NN/*.json, slurm/submissions.json) and a
// `batch --list` file.
inline constexpr InputLimit plan_file_limit{"plan file", std::uint64_t(64) << 20};
inline constexpr InputLimit list_file_limit{"list file", std::uint64_t(16) << 20};
// The CSV tables study, validate and collect read back (stats.csv, fronts).
inline constexpr InputLimit table_file_limit{"CSV table", std::uint64_t(1) << 30};
// render.font: the largest fonts (CJK collections) are about 30 MiB.
inline constexpr InputLimit font_file_limit{"font file", std::uint64_t(64) << 20};

// An input that cannot be read: `reason` says why, without the path (the
// caller names the file and the field).
struct FileReadError : std::runtime_error {
    std::filesystem::path path;
    std::string reason;
    FileReadError(std::filesystem::path path_, std::string reason_)
        : std::runtime_error(path_.string() + ": " + reason_), path(std::move(path_)),
          reason(std::move(reason_)) {}
};

// The whole of `path`, which must be a regular file (a symlink to one is
// fine) of at most `limit.bytes`. A device (/dev/zero), a FIFO, a socket or
// a folder is refused without reading it, and so is a larger file; a file
// that grows past the limit while it is read is refused too. Throws
// FileReadError.
std::string read_input_file(const std::filesystem::path& path, const InputLimit& limit);

// "16 MiB", "1.5 GiB": a byte count for messages.
std::string format_bytes(double bytes);

} // namespace sph
