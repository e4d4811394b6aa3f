#pragma once
// Messages to the terminal or a log that never fail the run: after a
// terminal closes or a pipe reader exits (SIGHUP, SIGPIPE), writing to it
// fails, and a run that is finishing its outputs must not stop over a
// progress line. fmt::print would throw there.

#include <cstdio>
#include <fmt/format.h>
#include <string>

namespace sph {

template <class... Args>
void say(std::FILE* stream, fmt::format_string<Args...> format, Args&&... args) {
    const std::string text = fmt::format(format, std::forward<Args>(args)...);
    if (std::fwrite(text.data(), 1, text.size(), stream) != text.size() || std::fflush(stream) != 0)
        std::clearerr(stream); // lost with the terminal; later lines try again
}

template <class... Args>
void say(fmt::format_string<Args...> format, Args&&... args) {
    say(stdout, format, std::forward<Args>(args)...);
}

} // namespace sph
