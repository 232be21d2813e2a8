#include "zenith/sky/gl/loader.h"

// zenith's own glad, renamed (cmake/ZenithGladPrefix.cmake): zenith_gladLoadGL, zenith_glad_gl*.
#include <glad/gl.h>

#include <string>

#include "gl/backends.h"
#include "zenith/sky/gl/error.h"

namespace zenith::sky::gl {
namespace {

GetProcAddressFn g_last_loader = nullptr;

GLADapiproc CallStdFunction(void* user, const char* name) {
    return (*static_cast<const std::function<GlProc(const char*)>*>(user))(name);
}

std::string GetString(GLenum name) {
    const GLubyte* text = glGetString(name);
    return text != nullptr ? reinterpret_cast<const char*>(text) : "(null)";
}

std::string ToString(GlVersion version) {
    return std::to_string(version.major) + "." + std::to_string(version.minor);
}

// Checks what zenith_gladLoadGL returned; `glad_version` is 0 when glGetString could not be loaded
// or returned nothing, which is what happens without a current context.
GlInfo CheckLoaded(int glad_version, GlVersion required) {
    if (glad_version == 0 || zenith_glad_glGetString == nullptr) {
        throw ContextError(
            "GL function loading failed: glGetString(GL_VERSION) gave nothing. Is a GL context "
            "current on this thread, and does the getProcAddress callback belong to its library?");
    }
    GlInfo info = QueryGlInfo();
    if (info.version < required) {
        throw ContextError("OpenGL " + ToString(required) + " is required, the context provides " +
                           Describe(info) +
                           ". Use Mesa >= 20 (llvmpipe) or a GPU driver with OpenGL " +
                           ToString(required) + ".");
    }
    // The loader reports a version once glGetString works; a broken callback shows up as null
    // pointers for the entry points that version promises.
    if (zenith_glad_glDispatchCompute == nullptr || zenith_glad_glCreateBuffers == nullptr ||
        zenith_glad_glGetNamedBufferSubData == nullptr) {
        throw ContextError("the context reports " + Describe(info) +
                           " but getProcAddress returned null for glDispatchCompute, "
                           "glCreateBuffers or glGetNamedBufferSubData");
    }
    return info;
}

}  // namespace

GlInfo LoadGlFunctions(GetProcAddressFn get_proc_address, GlVersion required) {
    if (get_proc_address == nullptr) throw ContextError("LoadGlFunctions: getProcAddress is null");
    g_last_loader = nullptr;
    GlInfo info = CheckLoaded(zenith_gladLoadGL(get_proc_address), required);
    g_last_loader = get_proc_address;
    return info;
}

GlInfo LoadGlFunctions(const std::function<GlProc(const char* name)>& get_proc_address,
                       GlVersion required) {
    if (!get_proc_address) throw ContextError("LoadGlFunctions: getProcAddress is empty");
    g_last_loader = nullptr;
    // glad only uses the callback during this call, so a pointer to the caller's object is safe.
    auto* user = const_cast<std::function<GlProc(const char*)>*>(&get_proc_address);
    return CheckLoaded(zenith_gladLoadGLUserPtr(&CallStdFunction, user), required);
}

GlInfo QueryGlInfo() {
    if (zenith_glad_glGetString == nullptr || zenith_glad_glGetIntegerv == nullptr) {
        throw GlError("QueryGlInfo: GL functions are not loaded (call LoadGlFunctions first)");
    }
    GlInfo info;
    GLint major = 0;
    GLint minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    info.version = {major, minor};
    info.version_string = GetString(GL_VERSION);
    info.renderer = GetString(GL_RENDERER);
    info.vendor = GetString(GL_VENDOR);
    info.shading_language = GetString(GL_SHADING_LANGUAGE_VERSION);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    info.core_profile = (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    return info;
}

std::string Describe(const GlInfo& info) {
    return "OpenGL " + info.version_string + " on " + info.renderer + " by " + info.vendor +
           (info.core_profile ? " (core profile)" : " (not core profile)");
}

namespace internal {

GetProcAddressFn LastLoader() { return g_last_loader; }

}  // namespace internal
}  // namespace zenith::sky::gl
