#include "gl/dynamic_library.h"

#include <dlfcn.h>

namespace zenith::sky::gl::internal {

DynamicLibrary DynamicLibrary::Open(std::initializer_list<const char*> names,
                                    std::string& attempts) {
    DynamicLibrary library;
    for (const char* name : names) {
        // A second dlopen of the same library returns the same handle: nothing is loaded twice.
        if (void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL)) {
            library.handle_ = handle;
            library.name_ = name;
            return library;
        }
        const char* error = dlerror();
        attempts += "  dlopen(\"" + std::string(name) +
                    "\"): " + (error != nullptr ? error : "unknown error") + "\n";
    }
    return library;
}

void* DynamicLibrary::FindRaw(const char* symbol) const {
    return handle_ != nullptr ? dlsym(handle_, symbol) : nullptr;
}

}  // namespace zenith::sky::gl::internal
