#include "io/png_io.hpp"

#include "io/files.hpp"

#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <libdeflate.h>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace {

// Level 1: on a 1280x720 frame (RGB), 17-28 ms against 21-107 ms for level 6,
// whose files are 2-10 % smaller; stb's own compressor takes 80-160 ms for
// files 20-55 % larger than level 1's. The writer thread shares the cores
// with the simulation, so its time counts more than the files' size.
constexpr int deflate_level = 1;

// stb_image_write's zlib step, done by libdeflate. stb frees the result with
// free(), hence malloc. Its `quality` (stb's own level) is ignored.
unsigned char* sphclip_zlib_compress(unsigned char* data, int data_len, int* out_len,
                                     int /*quality*/) {
    // A compressor is not thread-safe and is costly to set up: one per thread, kept.
    thread_local const std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)>
        compressor{libdeflate_alloc_compressor(deflate_level), libdeflate_free_compressor};
    if (!compressor)
        return nullptr;
    const std::size_t bound =
        libdeflate_zlib_compress_bound(compressor.get(), std::size_t(data_len));
    auto* out = static_cast<unsigned char*>(std::malloc(bound));
    if (!out)
        return nullptr;
    const std::size_t size =
        libdeflate_zlib_compress(compressor.get(), data, std::size_t(data_len), out, bound);
    if (size == 0 || size > std::size_t(INT_MAX)) {
        std::free(out);
        return nullptr;
    }
    *out_len = int(size);
    return out;
}

} // namespace

// The stb implementations live here only, with internal linkage, so that no
// other copy (another file's, Debian's libstb) can clash with them.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBIW_ZLIB_COMPRESS sphclip_zlib_compress
#include <stb_image_write.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO // read_png reads the file itself, to report why it cannot
#include <stb_image.h>

namespace sph {

namespace fs = std::filesystem;

void write_png(const fs::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4)
        throw std::invalid_argument("cannot write " + path.string() + ": image of " +
                                    std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " with " +
                                    std::to_string(image.rgba.size()) + " bytes of pixels");
    // stb counts the filtered rows' bytes in an int.
    if ((std::size_t(image.width) * 4 + 1) * std::size_t(image.height) > std::size_t(INT_MAX))
        throw std::runtime_error("cannot write " + path.string() + ": image too large for PNG (" +
                                 std::to_string(image.width) + "x" + std::to_string(image.height) +
                                 ")");

    bool opaque = true;
    for (std::size_t i = 3; i < image.rgba.size() && opaque; i += 4)
        opaque = image.rgba[i] == 255;
    const unsigned char* pixels = image.rgba.data();
    int channels = 4;
    std::vector<std::uint8_t> rgb;
    if (opaque) {
        rgb.resize(image.rgba.size() / 4 * 3);
        for (std::size_t src = 0, dst = 0; src < image.rgba.size(); src += 4, dst += 3) {
            rgb[dst] = image.rgba[src];
            rgb[dst + 1] = image.rgba[src + 1];
            rgb[dst + 2] = image.rgba[src + 2];
        }
        pixels = rgb.data();
        channels = 3;
    }

    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   std::size_t(size));
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, channels, pixels,
                                image.width * channels))
        throw std::runtime_error("cannot write " + path.string() +
                                 ": PNG encoding failed (out of memory?)");
    write_file_atomically(path, png);
}

Image read_png(const fs::path& path) {
    std::string bytes;
    try {
        bytes = read_input_file(path, png_file_limit);
    } catch (const FileReadError& e) {
        throw ImageReadError(path, e.reason);
    }
    return decode_png(bytes, path);
}

Image decode_png(std::string_view bytes, const fs::path& path) {
    // stb counts the file's bytes in an int.
    if (bytes.size() > std::size_t(INT_MAX))
        throw ImageReadError(path, "file too large");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    // The header's size first, from the IHDR chunk that must follow the
    // signature: a few bytes can claim an image of gigabytes.
    if (bytes.size() >= 24 && bytes.substr(0, 8) == "\x89PNG\r\n\x1a\n" &&
        bytes.substr(12, 4) == "IHDR") {
        const auto big_endian = [&](std::size_t at) {
            std::uint32_t v = 0;
            for (std::size_t k = 0; k < 4; ++k)
                v = v << 8 | std::uint8_t(bytes[at + k]);
            return v;
        };
        const std::uint32_t claimed_width = big_endian(16), claimed_height = big_endian(20);
        if (claimed_width > std::uint32_t(max_png_side) ||
            claimed_height > std::uint32_t(max_png_side) ||
            double(claimed_width) * double(claimed_height) > double(max_png_pixels))
            throw ImageReadError(path, fmt::format("the image is {}x{}; sphclip reads PNGs of at "
                                                   "most {} pixels a side and {} pixels in all",
                                                   claimed_width, claimed_height, max_png_side,
                                                   max_png_pixels));
    }
    int width = 0, height = 0, channels_in_file = 0;
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels{
        stbi_load_from_memory(data, int(bytes.size()), &width, &height, &channels_in_file, 4),
        stbi_image_free};
    if (!pixels) {
        const char* reason = stbi_failure_reason();
        throw ImageReadError(path, reason ? reason : "not a PNG");
    }
    Image image(width, height);
    std::memcpy(image.rgba.data(), pixels.get(), image.rgba.size());
    return image;
}

PngWriterThread::PngWriterThread(std::size_t capacity)
    : capacity_(capacity > 0 ? capacity : 1), worker_([this] { work(); }) {}

PngWriterThread::~PngWriterThread() {
    try {
        finish();
    } catch (...) {
        // A destructor may not throw; finish() is where callers see errors.
    }
}

void PngWriterThread::submit(fs::path path, Image image) {
    submit(std::move(path), std::make_shared<const Image>(std::move(image)));
}

void PngWriterThread::submit(fs::path path, std::shared_ptr<const Image> image) {
    if (!image)
        throw std::invalid_argument("PngWriterThread::submit without an image");
    std::unique_lock lock(mutex_);
    if (finished_)
        throw std::logic_error("PngWriterThread::submit after finish");
    taken_.wait(lock, [&] { return queue_.size() < capacity_ || error_; });
    if (error_)
        std::rethrow_exception(error_);
    queue_.push_back({std::move(path), std::move(image)});
    queued_.notify_one();
}

void PngWriterThread::finish() {
    {
        std::lock_guard lock(mutex_);
        if (finished_)
            return;
        finished_ = true;
        closing_ = true;
    }
    queued_.notify_one();
    worker_.join();
    if (error_)
        std::rethrow_exception(error_);
}

void PngWriterThread::work() {
    for (;;) {
        Job job;
        {
            std::unique_lock lock(mutex_);
            queued_.wait(lock, [&] { return !queue_.empty() || closing_; });
            if (queue_.empty())
                return;
            job = std::move(queue_.front());
            queue_.pop_front();
            if (error_) {
                taken_.notify_all();
                continue;
            }
        }
        taken_.notify_all();
        // Encoding and writing happen unlocked, so submit() can queue the next image meanwhile.
        try {
            write_png(job.path, *job.image);
        } catch (...) {
            std::lock_guard lock(mutex_);
            error_ = std::current_exception();
            taken_.notify_all();
        }
    }
}

} // namespace sph
