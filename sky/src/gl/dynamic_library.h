// dlopen/dlsym with error text, for GL libraries that are optional at run time.
#pragma once

#include <initializer_list>
#include <string>

namespace zenith::sky::gl::internal {

// A shared library opened once per process and never closed: Mesa and vendor GL libraries keep
// threads, TLS and atexit handlers that must outlive every context, and the loaded GL function
// pointers point into them.
class DynamicLibrary {
  public:
    // Tries `names` in order (RTLD_LOCAL, so their gl* symbols stay out of the global scope).
    // On failure returns a library with handle() == nullptr and appends one line per name tried
    // to `attempts`.
    static DynamicLibrary Open(std::initializer_list<const char*> names, std::string& attempts);

    void* handle() const { return handle_; }
    const std::string& name() const { return name_; }

    // Symbol by name, or nullptr.
    template <typename Fn>
    Fn Find(const char* symbol) const {
        // POSIX guarantees that a function's address survives the round trip through void*.
        return reinterpret_cast<Fn>(FindRaw(symbol));
    }

  private:
    void* FindRaw(const char* symbol) const;

    void* handle_ = nullptr;
    std::string name_;
};

}  // namespace zenith::sky::gl::internal
