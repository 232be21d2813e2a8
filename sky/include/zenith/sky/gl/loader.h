// GL function loading through a getProcAddress callback, so the renderer runs on zenith's own
// headless contexts and inside a host application's context alike.
//
// The function pointers are zenith's own and process-wide (a glad2 loader whose symbols are renamed
// zenith_glad*, so a host's glad, GLEW or epoxy neither clashes with them nor is touched by them):
// drive GL from one thread, and after switching to a context from another GL library (OSMesa <->
// EGL/libGL), load again. HeadlessContext does this in MakeCurrent(); a host that owns several
// contexts calls LoadGlFunctions() itself.
#pragma once

#include <functional>
#include <string>

namespace zenith::sky::gl {

// Same types as glad's GLADapiproc / GLADloadfunc, eglGetProcAddress, OSMesaGetProcAddress and
// glfwGetProcAddress, so those can be passed directly.
using GlProc = void (*)();
using GetProcAddressFn = GlProc (*)(const char* name);

struct GlVersion {
    int major = 0;
    int minor = 0;

    friend constexpr auto operator<=>(const GlVersion&, const GlVersion&) = default;
};

// Compute shaders (4.3), direct state access and clip control (4.5).
inline constexpr GlVersion kRequiredGlVersion{4, 5};

// What the current context reports about itself.
struct GlInfo {
    GlVersion version;             // parsed from GL_VERSION by the loader
    std::string version_string;    // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
    std::string renderer;          // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string vendor;            // GL_VENDOR
    std::string shading_language;  // GL_SHADING_LANGUAGE_VERSION
    bool core_profile = false;     // GL_CONTEXT_CORE_PROFILE_BIT set
};

// Loads every GL entry point for the context current on this thread through get_proc_address,
// and checks that the context provides at least `required`. Throws ContextError when no context
// is current, a core function is missing, or the version is too low; the message names the
// version and renderer found.
GlInfo LoadGlFunctions(GetProcAddressFn get_proc_address, GlVersion required = kRequiredGlVersion);

// The same for a host whose getProcAddress needs state (SDL, Qt's QOpenGLContext, ...).
GlInfo LoadGlFunctions(const std::function<GlProc(const char* name)>& get_proc_address,
                       GlVersion required = kRequiredGlVersion);

// GL_VERSION and friends of the current context; functions must have been loaded.
GlInfo QueryGlInfo();

// One line: "4.5 (Core Profile) Mesa 22.3.6 on llvmpipe (...) by Mesa".
std::string Describe(const GlInfo& info);

}  // namespace zenith::sky::gl
