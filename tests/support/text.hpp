#pragma once
// Small checks on text that many tests make of messages and files.

#include <string>

namespace sph::test {

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

} // namespace sph::test
