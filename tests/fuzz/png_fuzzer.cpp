// libFuzzer target for the PNG reader of `sphclip compare` (src/output/png_io.cpp,
// libpng underneath): any bytes must either give an image whose pixel
// buffer matches its size, or an ImageReadError. Another exception, a crash,
// undefined behaviour, a huge allocation or a hang is a finding. Built only
// with -DSPHCLIP_FUZZ=ON and clang; run with tests/fuzz/run_fuzzer.sh png SECONDS.

#include "output/png_io.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const sph::Image image = sph::decode_png(bytes, "fuzz.png");
        if (image.width <= 0 || image.height <= 0 || image.width > sph::max_png_side ||
            image.height > sph::max_png_side ||
            image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
            std::fprintf(stderr, "a decoded image of %dx%d holds %zu bytes\n", image.width,
                         image.height, image.rgba.size());
            std::abort();
        }
    } catch (const sph::ImageReadError&) {
        return 0; // the expected answer to a bad PNG
    }
    return 0;
}
