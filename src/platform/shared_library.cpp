#include "platform/shared_library.hpp"

#include <dlfcn.h>
#include <map>
#include <mutex>
#include <stdexcept>

namespace sph {

void* shared_library(const std::string& soname) {
    static std::mutex mutex;
    static std::map<std::string, void*> loaded;
    const std::lock_guard lock(mutex);
    if (const auto found = loaded.find(soname); found != loaded.end())
        return found->second;
    void* library = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        const char* reason = dlerror();
        throw std::runtime_error("cannot load the shared library " + soname + ": " +
                                 (reason ? reason : "no reason given"));
    }
    loaded.emplace(soname, library);
    return library;
}

void* library_symbol(void* library, const std::string& soname, const char* name) {
    dlerror(); // clears an earlier error
    void* symbol = dlsym(library, name);
    if (!symbol) {
        const char* reason = dlerror();
        throw std::runtime_error("the shared library " + soname + " has no " + name + ": " +
                                 (reason ? reason : "no reason given"));
    }
    return symbol;
}

} // namespace sph
