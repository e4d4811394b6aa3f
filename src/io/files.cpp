#include "io/files.hpp"

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

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
    const std::filesystem::path temporary = path.string() + ".partial";
    // O_NOFOLLOW: a link planted at the temporary name is not written through.
    const int fd =
        ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
    std::FILE* f = fd >= 0 ? ::fdopen(fd, "wb") : nullptr;
    if (!f && fd >= 0)
        ::close(fd);
    if (!f)
        throw std::runtime_error("cannot write " + temporary.string() + ": " +
                                 std::strerror(errno));
    const bool written = std::fwrite(content.data(), 1, content.size(), f) == content.size();
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) {
        std::remove(temporary.c_str());
        throw std::runtime_error("cannot write " + path.string() + " (disk full?)");
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec)
        throw std::runtime_error("cannot rename " + temporary.string() + ": " + ec.message());
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
        return FileReadError(path,
                             fmt::format("the file is {}; a {} is at most {}", format_bytes(size),
                                         limit.kind, format_bytes(double(limit.bytes))));
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
