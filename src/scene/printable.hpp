#pragma once
// Text from a user (a name, a key, a value) as a message may show it: a NUL
// would cut the message short where it is handed on as a C string, and other
// control characters could move a terminal's cursor or change its colours.
// They are written as JSON writes them (\u001b), as the user would type them
// in a scene; line breaks and tabs stay.

#include <fmt/format.h>
#include <string>
#include <string_view>

namespace sph {

inline std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f)
            out += fmt::format("\\u{:04x}", byte);
        else
            out += c;
    }
    return out;
}

} // namespace sph
