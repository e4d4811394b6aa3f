#include "cli/output_folder.hpp"

#include "output/files.hpp"
#include "scene/input_error.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <string_view>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sph {

namespace fs = std::filesystem;

namespace {

constexpr const char* lock_name = ".sphclip.lock";

// What a run writes at the folder's top, and whether each is a folder.
struct OutputName {
    const char* name;
    bool folder;
};
constexpr OutputName output_names[] = {
    {"frames", true},    {"particles", true},      {"stats.csv", false},  {"run.json", false},
    {"clip.mp4", false}, {"particles.pvd", false}, {"camera.csv", false}, {"surface", true},
};

[[noreturn]] void refuse(const fs::path& folder, const std::string& problem) {
    throw InputError("command line", "--out", fmt::format("{}: {}", folder.string(), problem));
}

// lstat: true when `path` exists; `info` says what it is, links not followed.
bool look(const fs::path& path, struct stat& info) {
    return ::lstat(path.c_str(), &info) == 0;
}

// The pid written in the lock file by the run that holds it ("?" if unreadable).
std::string holder_of(int fd) {
    char text[32] = {};
    const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
    std::string pid = n > 0 ? std::string(text, std::size_t(n)) : std::string();
    while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' '))
        pid.pop_back();
    return pid.empty() ? "?" : pid;
}

// True when folder/run.json is a run.json that sphclip wrote.
bool written_by_sphclip(const fs::path& run_json) {
    try {
        const auto document = nlohmann::json::parse(read_input_file(run_json, run_record_limit));
        return document.is_object() && document.contains("sphclip_version");
    } catch (const std::exception&) {
        return false;
    }
}

// A run's own files in frames/, particles/ or surface/:
// frame_NNNNN.png|csv|vtp|ply|vdb and their temporaries.
bool is_frame_file(const std::string& name) {
    if (!name.starts_with("frame_"))
        return false;
    std::string_view rest(name);
    if (rest.ends_with(".partial"))
        rest.remove_suffix(8);
    return rest.ends_with(".png") || rest.ends_with(".csv") || rest.ends_with(".vtp") ||
           rest.ends_with(".ply") || rest.ends_with(".vdb");
}

} // namespace

namespace {

// The folder made where it is missing, and writable.
void create_folder(const fs::path& folder) {
    std::error_code ec;
    // A run fills its folder with frames/, stats.csv, run.json...: the
    // filesystem's root (`--out /`, or a link to it) is never meant. Checked
    // first, so that the reason given is this one even where / is read-only.
    if (fs::equivalent(folder, "/", ec))
        throw InputError(
            "command line", "--out",
            fmt::format("{} is the filesystem's root; give the run a folder of its own",
                        folder.string()));
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder))
        throw InputError("command line", "--out",
                         fmt::format("cannot create the output folder {}: {}", folder.string(),
                                     ec ? ec.message() : "a file of that name exists"));
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw InputError("command line", "--out",
                         fmt::format("the output folder {} is not writable", folder.string()));
}

// Opens and locks folder/.sphclip.lock, with this process's pid in it; refuses
// a folder another run holds. Returns the lock file's descriptor.
int lock_folder(const fs::path& folder) {
    const fs::path lock = folder / lock_name;
    int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        refuse(folder,
               fmt::format("cannot open its lock file {}: {}", lock_name,
                           errno == ELOOP ? "it is a symbolic link" : std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        if (errno == EWOULDBLOCK) {
            const std::string pid = holder_of(fd);
            ::close(fd);
            fd = -1;
            refuse(folder, fmt::format("another sphclip run (pid {}) is writing to this folder; "
                                       "wait for it to end or give another --out",
                                       pid));
        }
        // A filesystem without locks: runs are not kept apart there.
    }
    const std::string pid = fmt::format("{}\n", ::getpid());
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
        // The pid is for the message of a refused run only; the lock holds.
    }
    return fd;
}

// Refuses a link or an entry of the wrong type under any name a run writes.
// Returns whether outputs of an earlier run (or a user's) are there.
bool check_output_names(const fs::path& folder) {
    std::error_code ec;
    // Every name a run writes: no link, no entry of the wrong type.
    bool earlier_outputs = false;
    for (const auto& [name, is_folder] : output_names) {
        struct stat info {};
        const fs::path path = folder / name;
        for (const fs::path& p : {path, fs::path(path.string() + ".partial")}) {
            if (!look(p, info))
                continue;
            if (S_ISLNK(info.st_mode))
                refuse(folder, fmt::format("{} is a symbolic link; sphclip never writes through "
                                           "a link in its output folder: remove it or give "
                                           "another --out",
                                           p.filename().string()));
            if (p == path && is_folder != S_ISDIR(info.st_mode))
                refuse(folder, fmt::format("{} is {} where a run writes {}: remove it or give "
                                           "another --out",
                                           name, S_ISDIR(info.st_mode) ? "a folder" : "a file",
                                           is_folder ? "a folder" : "a file"));
            // A pipe, a socket or a device under a run's name is no run's:
            // neither written to nor removed.
            if (!S_ISDIR(info.st_mode) && !S_ISREG(info.st_mode))
                refuse(folder, fmt::format("{} is not a regular file (a pipe, a socket or a "
                                           "device) where a run writes a file: remove it or "
                                           "give another --out",
                                           p.filename().string()));
        }
        if (!look(path, info))
            continue;
        if (!is_folder) {
            earlier_outputs = true;
            continue;
        }
        // Found now, not at the first frame after the run has begun.
        if (::access(path.c_str(), W_OK | X_OK) != 0)
            refuse(folder, fmt::format("{}/ is not writable ({}): make it writable, remove it or "
                                       "give another --out",
                                       name, std::strerror(errno)));
        for (const auto& entry : fs::directory_iterator(path, ec)) {
            struct stat inner {};
            if (!is_frame_file(entry.path().filename().string()) || !look(entry.path(), inner))
                continue;
            if (S_ISLNK(inner.st_mode) || !S_ISREG(inner.st_mode))
                refuse(folder, fmt::format("{}/{} is {}; sphclip writes only regular files "
                                           "there: remove it or give another --out",
                                           name, entry.path().filename().string(),
                                           S_ISLNK(inner.st_mode) ? "a symbolic link"
                                                                  : "not a regular file"));
            earlier_outputs = true;
        }
    }
    return earlier_outputs;
}

// Removes an earlier sphclip run's outputs (refusing a folder whose outputs
// no sphclip run made). Returns what was replaced, for the run's message.
std::vector<std::string> remove_earlier_outputs(const fs::path& folder) {
    std::error_code ec;
    std::vector<std::string> replaced;
    // Outputs are there: an earlier run's, or a user's.
    if (!written_by_sphclip(folder / "run.json"))
        refuse(folder, "it holds files with the names a run writes (frames/frame_*, stats.csv, "
                       "run.json, clip.mp4, particles...) but no run.json of a sphclip run: "
                       "sphclip does not overwrite files it did not make; give another --out");
    for (const auto& [name, is_folder] : output_names) {
        const fs::path path = folder / name;
        if (is_folder) {
            std::size_t removed = 0;
            for (const auto& entry : fs::directory_iterator(path, ec))
                if (is_frame_file(entry.path().filename().string()) && fs::remove(entry.path(), ec))
                    ++removed;
            if (removed > 0)
                replaced.push_back(fmt::format("{}/ ({} files)", name, removed));
            continue;
        }
        for (const fs::path& p : {path, fs::path(path.string() + ".partial")})
            if (p.filename() != "run.json" && fs::remove(p, ec))
                replaced.push_back(p.filename().string());
    }
    return replaced;
}

} // namespace

OutputFolder::OutputFolder(fs::path folder) : folder_(std::move(folder)) {
    create_folder(folder_);
    // The lock first: what follows must not race another run's.
    lock_fd_ = lock_folder(folder_);
    if (check_output_names(folder_))
        replaced_ = remove_earlier_outputs(folder_);
}

OutputFolder::~OutputFolder() {
    // The lock file stays: removing it would let a third run lock a new
    // file while a second still waits on the old one.
    if (lock_fd_ >= 0)
        ::close(lock_fd_);
}

} // namespace sph
