#include "output/libav_handles.hpp"
#include "platform/shared_library.hpp"

#include <string>

namespace sph::libav {

namespace {

std::string soname(std::string_view library) {
    const int major = library == "avcodec"    ? LIBAVCODEC_VERSION_MAJOR
                      : library == "avformat" ? LIBAVFORMAT_VERSION_MAJOR
                      : library == "avutil"   ? LIBAVUTIL_VERSION_MAJOR
                                              : LIBSWSCALE_VERSION_MAJOR;
    return "lib" + std::string(library) + ".so." + std::to_string(major);
}

Functions load() {
    Functions f;
#define SPHCLIP_LIBAV_LOAD(library, name)                                                          \
    f.name = library_function<decltype(&::name)>(soname(#library), #name);
    SPHCLIP_LIBAV_FUNCTIONS(SPHCLIP_LIBAV_LOAD)
#undef SPHCLIP_LIBAV_LOAD
    return f;
}

} // namespace

const Functions& functions() {
    static const Functions loaded = load(); // thread-safe; a throw retries next time
    return loaded;
}

} // namespace sph::libav
