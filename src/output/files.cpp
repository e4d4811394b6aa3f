#include "output/files.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace sph {

bool is_out_of_space(int error) {
    return error == ENOSPC || error == EDQUOT || error == EFBIG;
}

void throw_write_error(const std::filesystem::path& path, int error) {
    const std::string message = fmt::format("cannot write {}: {}", path.string(),
                                            error ? std::strerror(error) : "unknown error");
    if (is_out_of_space(error))
        throw OutOfSpaceError(path, error, message);
    throw std::runtime_error(message);
}

namespace {

// Writes all of `content` at `offset`; the errno of a failure, 0 on success.
int write_all(int fd, std::string_view content, off_t offset) {
    while (!content.empty()) {
        const ssize_t n = ::pwrite(fd, content.data(), content.size(), offset);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return n < 0 ? errno : ENOSPC;
        content.remove_prefix(std::size_t(n));
        offset += n;
    }
    return 0;
}

} // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
    const std::filesystem::path temporary = path.string() + ".partial";
    // O_NOFOLLOW: a link planted at the temporary name is not written through.
    const int fd =
        ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        throw_write_error(temporary, errno);
    int error = write_all(fd, content, 0);
    if (::close(fd) != 0 && error == 0)
        error = errno;
    if (error != 0) {
        // Removed: a half-written file is never left, and its blocks are free again.
        std::remove(temporary.c_str());
        throw_write_error(path, error);
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec)
        throw std::runtime_error("cannot rename " + temporary.string() + ": " + ec.message());
}

void write_file_in_place(const std::filesystem::path& path, std::string_view content) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        throw std::runtime_error(
            fmt::format("cannot rewrite {}: {}", path.string(), std::strerror(errno)));
    struct stat info {};
    int error = ::fstat(fd, &info) != 0 ? errno : 0;
    if (error == 0 && (!S_ISREG(info.st_mode) || std::uint64_t(info.st_size) < content.size())) {
        ::close(fd);
        throw std::runtime_error(fmt::format("cannot rewrite {} in place: {} bytes do not fit in "
                                             "its {}",
                                             path.string(), content.size(),
                                             format_bytes(double(info.st_size))));
    }
    if (error == 0)
        error = write_all(fd, content, 0);
    if (error == 0 && ::ftruncate(fd, off_t(content.size())) != 0)
        error = errno;
    if (::close(fd) != 0 && error == 0)
        error = errno;
    if (error != 0)
        throw std::runtime_error(
            fmt::format("cannot rewrite {}: {}", path.string(), std::strerror(error)));
}

std::string format_bytes(double bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (bytes >= 1024 && u < 4) {
        bytes /= 1024;
        ++u;
    }
    return u == 0 ? fmt::format("{:.0f} bytes", bytes) : fmt::format("{:.3g} {}", bytes, units[u]);
}

std::string read_input_file(const std::filesystem::path& path, const InputLimit& limit) {
    // O_NONBLOCK: opening a FIFO with no writer would otherwise wait forever;
    // it is refused below as not a regular file.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw FileReadError(path, std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat info {};
    if (::fstat(fd, &info) != 0)
        throw FileReadError(path, std::strerror(errno));
    if (S_ISDIR(info.st_mode))
        throw FileReadError(path, "it is a folder, not a file");
    if (!S_ISREG(info.st_mode))
        throw FileReadError(path, fmt::format("not a regular file (a device, a pipe or a socket); "
                                              "a {} must be a regular file",
                                              limit.kind));
    const auto too_large = [&](double size) {
        // In bytes too where rounding would hide the excess ("16 MiB; at most 16 MiB").
        const std::string is = size < 1024
                                   ? format_bytes(size)
                                   : fmt::format("{} ({:.0f} bytes)", format_bytes(size), size);
        return FileReadError(path, fmt::format("the file is {}; a {} is at most {}", is, limit.kind,
                                               format_bytes(double(limit.bytes))));
    };
    if (std::uint64_t(info.st_size) > limit.bytes)
        throw too_large(double(info.st_size));
    std::string bytes;
    bytes.reserve(std::size_t(info.st_size));
    char buffer[1 << 16];
    while (true) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            throw FileReadError(path, std::strerror(errno));
        }
        if (n == 0)
            break;
        bytes.append(buffer, std::size_t(n));
        if (bytes.size() > limit.bytes) // it grew while being read
            throw too_large(double(bytes.size()));
    }
    return bytes;
}

} // namespace sph
