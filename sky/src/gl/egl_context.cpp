// EGL: OpenGL without a window system, through EGL_MESA_platform_surfaceless (Mesa) or
// EGL_EXT_platform_device (NVIDIA's headless path; Mesa lists its devices too). libEGL (glvnd) is
// opened at run time; contexts are made current without a surface (EGL_KHR_surfaceless_context).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "gl/backends.h"
#include "gl/dynamic_library.h"

namespace zenith::sky::gl::internal {
namespace {

constexpr const char* kInstallHint =
    "Install EGL with an OpenGL vendor library: Mesa (Debian/Ubuntu: apt-get install libegl1 "
    "libegl-mesa0) or the NVIDIA driver's EGL (libEGL_nvidia.so.0, listed in "
    "/usr/share/glvnd/egl_vendor.d), pick another platform with ZENITH_EGL_PLATFORM="
    "auto|surfaceless|device|device:N, or use ZENITH_GL=osmesa.";

struct EglApi {
    DynamicLibrary library;
    PFNEGLGETPROCADDRESSPROC get_proc_address = nullptr;
    PFNEGLGETERRORPROC get_error = nullptr;
    PFNEGLQUERYSTRINGPROC query_string = nullptr;
    PFNEGLGETPLATFORMDISPLAYPROC get_platform_display = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLTERMINATEPROC terminate = nullptr;
    PFNEGLBINDAPIPROC bind_api = nullptr;
    PFNEGLCHOOSECONFIGPROC choose_config = nullptr;
    PFNEGLCREATECONTEXTPROC create_context = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroy_context = nullptr;
    PFNEGLMAKECURRENTPROC make_current = nullptr;
    PFNEGLGETCURRENTCONTEXTPROC get_current_context = nullptr;
    // EGL_EXT_device_enumeration / EGL_EXT_device_query; null when absent.
    PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
    std::string client_extensions;
};

bool HasExtension(std::string_view extensions, std::string_view name) {
    size_t start = 0;
    while (start < extensions.size()) {
        size_t end = extensions.find(' ', start);
        if (end == std::string_view::npos) end = extensions.size();
        if (extensions.substr(start, end - start) == name) return true;
        start = end + 1;
    }
    return false;
}

const EglApi& Api() {
    static const EglApi api = [] {
        EglApi result;
        std::string attempts;
        result.library = DynamicLibrary::Open({"libEGL.so.1", "libEGL.so"}, attempts);
        if (result.library.handle() == nullptr) {
            throw ContextError("EGL context: libEGL could not be loaded.\n" + attempts +
                               kInstallHint);
        }
        const DynamicLibrary& lib = result.library;
        result.get_proc_address = lib.Find<PFNEGLGETPROCADDRESSPROC>("eglGetProcAddress");
        result.get_error = lib.Find<PFNEGLGETERRORPROC>("eglGetError");
        result.query_string = lib.Find<PFNEGLQUERYSTRINGPROC>("eglQueryString");
        result.get_platform_display =
            lib.Find<PFNEGLGETPLATFORMDISPLAYPROC>("eglGetPlatformDisplay");
        result.initialize = lib.Find<PFNEGLINITIALIZEPROC>("eglInitialize");
        result.terminate = lib.Find<PFNEGLTERMINATEPROC>("eglTerminate");
        result.bind_api = lib.Find<PFNEGLBINDAPIPROC>("eglBindAPI");
        result.choose_config = lib.Find<PFNEGLCHOOSECONFIGPROC>("eglChooseConfig");
        result.create_context = lib.Find<PFNEGLCREATECONTEXTPROC>("eglCreateContext");
        result.destroy_context = lib.Find<PFNEGLDESTROYCONTEXTPROC>("eglDestroyContext");
        result.make_current = lib.Find<PFNEGLMAKECURRENTPROC>("eglMakeCurrent");
        result.get_current_context = lib.Find<PFNEGLGETCURRENTCONTEXTPROC>("eglGetCurrentContext");
        if (result.get_proc_address == nullptr || result.get_error == nullptr ||
            result.query_string == nullptr || result.get_platform_display == nullptr ||
            result.initialize == nullptr || result.terminate == nullptr ||
            result.bind_api == nullptr || result.choose_config == nullptr ||
            result.create_context == nullptr || result.destroy_context == nullptr ||
            result.make_current == nullptr || result.get_current_context == nullptr) {
            throw ContextError("EGL context: " + lib.name() +
                               " lacks EGL 1.5 entry points (eglGetPlatformDisplay, ...). " +
                               kInstallHint);
        }
        // Client extensions (EGL 1.5 / EGL_EXT_client_extensions): which platforms exist.
        const char* client = result.query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        result.client_extensions = client != nullptr ? client : "";
        result.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(
            result.get_proc_address("eglQueryDevicesEXT"));
        result.query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
            result.get_proc_address("eglQueryDeviceStringEXT"));
        return result;
    }();
    return api;
}

std::string EglErrorName(EGLint error) {
    switch (error) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE:
            return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP:
            return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW:
            return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST:
            return "EGL_CONTEXT_LOST";
        default:
            return "EGL error " + std::to_string(error);
    }
}

std::string LastError(const EglApi& api) { return EglErrorName(api.get_error()); }

// eglTerminate is per display, not per context, and eglGetPlatformDisplay returns the same
// display for the same arguments: count the contexts on each so one does not pull the display
// from under another.
class DisplayRegistry {
  public:
    void Acquire(EGLDisplay display) {
        std::lock_guard lock(mutex_);
        ++count_[display];
    }
    void Release(const EglApi& api, EGLDisplay display) {
        std::lock_guard lock(mutex_);
        if (--count_[display] == 0) {
            count_.erase(display);
            api.terminate(display);
        }
    }

  private:
    std::mutex mutex_;
    std::map<EGLDisplay, int> count_;
};

DisplayRegistry& Displays() {
    static DisplayRegistry registry;
    return registry;
}

struct Candidate {
    std::string label;  // for messages: "surfaceless", "device 0 (/dev/dri/card0)"
    EGLenum platform;
    void* native_display;
};

std::vector<Candidate> ListCandidates(const EglApi& api, const EglOptions& options,
                                      std::string& attempts) {
    std::vector<Candidate> hardware;
    std::vector<Candidate> software;
    std::vector<Candidate> chosen_device;
    const bool want_devices = options.platform != EglPlatform::kSurfaceless;
    if (want_devices) {
        if (!HasExtension(api.client_extensions, "EGL_EXT_platform_device") ||
            api.query_devices == nullptr || api.query_device_string == nullptr) {
            attempts +=
                "  device platform: libEGL offers no EGL_EXT_platform_device with "
                "EGL_EXT_device_enumeration (client extensions: " +
                api.client_extensions + ")\n";
        } else {
            EGLint count = 0;
            std::vector<EGLDeviceEXT> devices(16);
            if (!api.query_devices(static_cast<EGLint>(devices.size()), devices.data(), &count)) {
                attempts +=
                    "  device platform: eglQueryDevicesEXT failed: " + LastError(api) + "\n";
                count = 0;
            }
            devices.resize(static_cast<size_t>(count));
            if (options.platform == EglPlatform::kDevice && options.device_index >= count) {
                attempts += "  device " + std::to_string(options.device_index) +
                            ": requested, but eglQueryDevicesEXT lists " + std::to_string(count) +
                            " device(s) (valid: 0.." + std::to_string(count - 1) + ")\n";
            }
            for (EGLint i = 0; i < count; ++i) {
                EGLDeviceEXT device = devices[static_cast<size_t>(i)];
                const char* extensions_c = api.query_device_string(device, EGL_EXTENSIONS);
                const std::string extensions = extensions_c != nullptr ? extensions_c : "";
                const bool is_software = HasExtension(extensions, "EGL_MESA_device_software");
                std::string label = "device " + std::to_string(i);
                if (HasExtension(extensions, "EGL_EXT_device_drm")) {
                    const char* file = api.query_device_string(device, EGL_DRM_DEVICE_FILE_EXT);
                    if (file != nullptr) label += std::string(" (") + file + ")";
                } else if (is_software) {
                    label += " (Mesa software)";
                }
                Candidate candidate{label, EGL_PLATFORM_DEVICE_EXT, device};
                if (options.platform == EglPlatform::kDevice && options.device_index >= 0) {
                    if (i == options.device_index) chosen_device.push_back(candidate);
                } else {
                    (is_software ? software : hardware).push_back(candidate);
                }
            }
        }
    }
    if (options.platform == EglPlatform::kDevice) {
        if (options.device_index >= 0) return chosen_device;
        hardware.insert(hardware.end(), software.begin(), software.end());
        return hardware;
    }
    std::vector<Candidate> result = hardware;
    if (HasExtension(api.client_extensions, "EGL_MESA_platform_surfaceless")) {
        result.push_back({"surfaceless", EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY});
    } else {
        attempts +=
            "  surfaceless: libEGL offers no EGL_MESA_platform_surfaceless (client "
            "extensions: " +
            api.client_extensions + ")\n";
        // Mesa's software device is the same llvmpipe, reachable without the surfaceless platform.
        if (options.platform == EglPlatform::kAuto) {
            result.insert(result.end(), software.begin(), software.end());
        }
    }
    return result;
}

class EglContext final : public HeadlessContext {
  public:
    EglContext(const EglApi& api, EGLDisplay display, EGLContext context, std::string description)
        : HeadlessContext(ContextKind::kEgl, std::move(description)),
          api_(api),
          display_(display),
          context_(context) {
        Displays().Acquire(display_);
    }

    ~EglContext() override {
        if (api_.get_current_context() == context_) ReleaseCurrentImpl();
        api_.destroy_context(display_, context_);
        Displays().Release(api_, display_);
    }

    GetProcAddressFn get_proc_address() const override { return api_.get_proc_address; }

    using HeadlessContext::Initialize;

  protected:
    void MakeCurrentImpl() override {
        // The bound API is per thread, and eglGetCurrentContext answers for the bound API.
        api_.bind_api(EGL_OPENGL_API);
        if (!api_.make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
            throw ContextError("EGL context: eglMakeCurrent failed: " + LastError(api_));
        }
    }

    void ReleaseCurrentImpl() override {
        api_.bind_api(EGL_OPENGL_API);
        api_.make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }

  private:
    const EglApi& api_;
    EGLDisplay display_;
    EGLContext context_;
};

// One platform/device; nullptr with a line appended to `attempts` when it does not work.
std::unique_ptr<HeadlessContext> TryCandidate(const EglApi& api, const Candidate& candidate,
                                              const ContextOptions& options,
                                              std::string& attempts) {
    auto fail = [&](const std::string& why) {
        attempts += "  " + candidate.label + ": " + why + "\n";
        return nullptr;
    };
    EGLDisplay display =
        api.get_platform_display(candidate.platform, candidate.native_display, nullptr);
    if (display == EGL_NO_DISPLAY) return fail("eglGetPlatformDisplay: " + LastError(api));
    EGLint egl_major = 0;
    EGLint egl_minor = 0;
    if (!api.initialize(display, &egl_major, &egl_minor)) {
        return fail("eglInitialize: " + LastError(api));
    }
    // From here the display is initialised: the registry terminates it with its last context.
    Displays().Acquire(display);
    struct ReleaseDisplay {
        const EglApi& api;
        EGLDisplay display;
        ~ReleaseDisplay() { Displays().Release(api, display); }
    } release_display{api, display};

    const char* vendor_c = api.query_string(display, EGL_VENDOR);
    const char* extensions_c = api.query_string(display, EGL_EXTENSIONS);
    const std::string vendor = vendor_c != nullptr ? vendor_c : "unknown vendor";
    const std::string extensions = extensions_c != nullptr ? extensions_c : "";
    const std::string where =
        "EGL " + std::to_string(egl_major) + "." + std::to_string(egl_minor) + " (" + vendor + ")";
    if (!HasExtension(extensions, "EGL_KHR_surfaceless_context")) {
        return fail(where + ": no EGL_KHR_surfaceless_context");
    }
    if (!api.bind_api(EGL_OPENGL_API)) {
        return fail(where + ": eglBindAPI(EGL_OPENGL_API): " + LastError(api) +
                    " (an OpenGL ES-only driver?)");
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!HasExtension(extensions, "EGL_KHR_no_config_context")) {
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                         EGL_PBUFFER_BIT, EGL_NONE};
        EGLint count = 0;
        if (!api.choose_config(display, config_attribs, &config, 1, &count) || count < 1) {
            return fail(where + ": eglChooseConfig found no OpenGL config: " + LastError(api));
        }
    }
    // Attribute lists as key, value rows.
    // clang-format off
    const EGLint context_attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,       options.version.major,
        EGL_CONTEXT_MINOR_VERSION,       options.version.minor,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_CONTEXT_OPENGL_DEBUG,        options.debug ? EGL_TRUE : EGL_FALSE,
        EGL_NONE,
    };
    // clang-format on
    EGLContext context = api.create_context(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) {
        return fail(where + ": eglCreateContext(OpenGL " + std::to_string(options.version.major) +
                    "." + std::to_string(options.version.minor) + " core): " + LastError(api));
    }
    auto result =
        std::make_unique<EglContext>(api, display, context, where + ", " + candidate.label);
    try {
        result->Initialize(options.version);
    } catch (const ContextError& error) {
        return fail(error.what());
    }
    return result;
}

}  // namespace

std::unique_ptr<HeadlessContext> CreateEglContext(const ContextOptions& options) {
    const EglApi& api = Api();
    std::string attempts;
    for (const Candidate& candidate : ListCandidates(api, options.egl, attempts)) {
        if (auto context = TryCandidate(api, candidate, options, attempts)) return context;
    }
    throw ContextError("EGL context: no OpenGL " + std::to_string(options.version.major) + "." +
                       std::to_string(options.version.minor) +
                       " core context could be created with " + api.library.name() + ". Tried:\n" +
                       attempts + kInstallHint);
}

}  // namespace zenith::sky::gl::internal
