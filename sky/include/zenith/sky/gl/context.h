// Headless OpenGL 4.5 core contexts behind one interface: OSMesa (llvmpipe, the default; needs no
// display and no GPU) and EGL (Mesa's surfaceless platform, or EGL_EXT_platform_device, which is
// how NVIDIA's driver runs without X).
//
// The renderer draws into its own FBOs, so a context only has to be current: neither kind has a
// usable default framebuffer. OSMesa and EGL are opened at run time (dlopen), so a program that
// only renders into a host's context needs neither library, and a missing one is a ContextError
// that says what to install rather than a loader failure at start-up.
//
// Environment (read by the *FromEnvironment functions):
//   ZENITH_GL            osmesa | egl                          (default osmesa)
//   ZENITH_EGL_PLATFORM  auto | surfaceless | device | device:N  (default auto: a hardware EGL
//                        device first, then surfaceless)
// llvmpipe's own LP_NUM_THREADS (default: every core) sets its rasteriser threads.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "zenith/base/error.h"
#include "zenith/sky/gl/error.h"
#include "zenith/sky/gl/loader.h"

namespace zenith::sky::gl {

enum class ContextKind {
    kOsMesa,
    kEgl,
};

// "osmesa" | "egl"; anything else throws zenith::ArgumentError naming the value and the choices.
ContextKind ParseContextKind(std::string_view name);
std::string_view ToString(ContextKind kind);
// ZENITH_GL, or kOsMesa when unset or empty; a bad value throws as ParseContextKind does.
ContextKind ContextKindFromEnvironment();

enum class EglPlatform {
    kAuto,         // hardware EGL devices in order, then surfaceless
    kDevice,       // EGL_EXT_platform_device (NVIDIA headless; Mesa also lists a software device)
    kSurfaceless,  // EGL_MESA_platform_surfaceless (Mesa)
};

struct EglOptions {
    EglPlatform platform = EglPlatform::kAuto;
    int device_index = -1;  // with kDevice: index into eglQueryDevicesEXT; -1 = first that works
};

// "auto" | "surfaceless" | "device" | "device:N"; anything else throws zenith::ArgumentError.
EglOptions ParseEglOptions(std::string_view text);
// ZENITH_EGL_PLATFORM, or the defaults when unset or empty.
EglOptions EglOptionsFromEnvironment();

struct ContextOptions {
    ContextKind kind = ContextKind::kOsMesa;
    EglOptions egl;
    GlVersion version = kRequiredGlVersion;  // core profile, at least this
    bool debug = false;                      // a debug context (KHR_debug output is useful)
};

// An offscreen GL context that owns its library handles. Not copyable or movable: the GL state
// it owns lives as long as it does. Use from one thread at a time.
class HeadlessContext {
  public:
    virtual ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    // Makes the context current on this thread and (re)loads the GL functions when the last
    // loaded ones came from another GL library. A context of the other kind that is current on
    // this thread is released first. Throws ContextError on failure.
    void MakeCurrent();
    // Leaves no context current on this thread (for handing the thread to a host).
    void ReleaseCurrent();

    ContextKind kind() const { return kind_; }
    // Which library/platform/device the context came from, e.g. "EGL 1.5 (Mesa Project),
    // platform surfaceless" or "OSMesa (libOSMesa.so.8)".
    const std::string& description() const { return description_; }
    // GL_VERSION, GL_RENDERER, ... as queried when the context was created.
    const GlInfo& info() const { return info_; }
    // The callback GL functions are loaded through; hand it to a library that loads its own.
    virtual GetProcAddressFn get_proc_address() const = 0;

  protected:
    HeadlessContext(ContextKind kind, std::string description)
        : kind_(kind), description_(std::move(description)) {}

    virtual void MakeCurrentImpl() = 0;
    virtual void ReleaseCurrentImpl() = 0;
    // Called by the factory to make the new context current, load the GL functions and check
    // the version.
    void Initialize(GlVersion required);

  private:
    ContextKind kind_;
    std::string description_;
    GlVersion required_ = kRequiredGlVersion;
    GlInfo info_;
};

// Creates a context of the given kind with default options, makes it current and loads the GL
// functions. Throws ContextError that lists every attempt and what to install.
std::unique_ptr<HeadlessContext> CreateHeadlessContext(ContextKind kind);
std::unique_ptr<HeadlessContext> CreateHeadlessContext(const ContextOptions& options);
// Kind from ZENITH_GL and EGL options from ZENITH_EGL_PLATFORM.
std::unique_ptr<HeadlessContext> CreateHeadlessContextFromEnvironment();

}  // namespace zenith::sky::gl
