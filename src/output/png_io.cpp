#include "output/png_io.hpp"

#include "output/files.hpp"

#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <libdeflate.h>
#include <memory>
#include <png.h>
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

namespace {

// libpng reports errors by longjmp; the message is kept here first. Only C
// data lives between setjmp and the calls that may jump back to it.
struct PngReadState {
    const unsigned char* data;
    std::size_t size;
    std::size_t at;
    char message[256];
};

extern "C" void png_read_from_memory(png_structp png, png_bytep out, png_size_t length) {
    auto* state = static_cast<PngReadState*>(png_get_io_ptr(png));
    if (length > state->size - state->at)
        png_error(png, "the file ends inside a chunk");
    std::memcpy(out, state->data + state->at, length);
    state->at += length;
}

extern "C" void png_keep_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngReadState*>(png_get_io_ptr(png));
    std::snprintf(state->message, sizeof state->message, "%s", message);
    png_longjmp(png, 1);
}

extern "C" void png_ignore_warning(png_structp, png_const_charp) {}

// Decodes into `rgba`, sized once the header is read; `rows` points into it.
// Both belong to the caller, so that nothing but C data changes in this
// frame between setjmp and a longjmp. Returns false with state.message set on
// any error.
bool decode_with_libpng(PngReadState& state, std::vector<std::uint8_t>& rgba,
                        std::vector<png_bytep>& rows, int& width, int& height) {
    png_structp png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, png_keep_error, png_ignore_warning);
    if (!png) {
        std::snprintf(state.message, sizeof state.message, "out of memory");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
        return false;
    }
    png_set_read_fn(png, &state, png_read_from_memory);
    png_set_user_limits(png, max_png_side, max_png_side);
    // Ancillary chunks (text, ICC profiles) are bounded too: a few bytes
    // of a compressed chunk may claim gigabytes.
    png_set_chunk_malloc_max(png, png_alloc_size_t(64) << 20);
    png_read_info(png, info);
    const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    // Every form as 8-bit RGBA, with no gamma conversion: palettes and
    // low bit depths expanded, tRNS as alpha, 16 bits cut to their high byte.
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != std::size_t(w) * 4)
        png_error(png, "unexpected row layout after conversion to RGBA");
    width = int(w);
    height = int(h);
    rgba.assign(std::size_t(w) * std::size_t(h) * 4, 0);
    rows.resize(h);
    for (png_uint_32 y = 0; y < h; ++y)
        rows[y] = rgba.data() + std::size_t(y) * std::size_t(w) * 4;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

} // namespace

Image decode_png(std::string_view bytes, const fs::path& path) {
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
    if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8))
        throw ImageReadError(path, "not a PNG (no PNG signature)");
    PngReadState state{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 0, {}};
    std::vector<std::uint8_t> rgba;
    std::vector<png_bytep> rows;
    int width = 0, height = 0;
    if (!decode_with_libpng(state, rgba, rows, width, height))
        throw ImageReadError(path, state.message[0] ? state.message : "not a readable PNG");
    Image image(width, height);
    image.rgba = std::move(rgba);
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
