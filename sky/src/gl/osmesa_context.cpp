// OSMesa: Mesa's off-screen interface, rendering with llvmpipe on the CPU. Needs no display, no
// GPU and no DRI drivers; libOSMesa is opened at run time.
#include <GL/osmesa.h>  // types and constants only: every function comes from dlsym

#include <array>
#include <string>
#include <vector>

#include "gl/backends.h"
#include "gl/dynamic_library.h"

namespace zenith::sky::gl::internal {
namespace {

constexpr const char* kInstallHint =
    "Install Mesa's OSMesa (Debian/Ubuntu: apt-get install libosmesa6; Fedora: mesa-libOSMesa), "
    "or set ZENITH_GL=egl to use EGL instead.";

// OSMesaMakeCurrent needs a colour buffer; the renderer draws into its own FBOs, so a tiny one.
constexpr int kBufferSize = 4;

struct OsMesaApi {
    DynamicLibrary library;
    decltype(&OSMesaCreateContextAttribs) create_context_attribs = nullptr;
    decltype(&OSMesaDestroyContext) destroy_context = nullptr;
    decltype(&OSMesaMakeCurrent) make_current = nullptr;
    decltype(&OSMesaGetCurrentContext) get_current_context = nullptr;
    decltype(&OSMesaGetProcAddress) get_proc_address = nullptr;
};

// Opened once; throws ContextError when the library or an entry point is missing.
const OsMesaApi& Api() {
    static const OsMesaApi api = [] {
        OsMesaApi result;
        std::string attempts;
        result.library = DynamicLibrary::Open({"libOSMesa.so.8", "libOSMesa.so"}, attempts);
        if (result.library.handle() == nullptr) {
            throw ContextError("OSMesa context: libOSMesa could not be loaded.\n" + attempts +
                               kInstallHint);
        }
        const DynamicLibrary& lib = result.library;
        result.create_context_attribs =
            lib.Find<decltype(result.create_context_attribs)>("OSMesaCreateContextAttribs");
        result.destroy_context = lib.Find<decltype(result.destroy_context)>("OSMesaDestroyContext");
        result.make_current = lib.Find<decltype(result.make_current)>("OSMesaMakeCurrent");
        result.get_current_context =
            lib.Find<decltype(result.get_current_context)>("OSMesaGetCurrentContext");
        result.get_proc_address =
            lib.Find<decltype(result.get_proc_address)>("OSMesaGetProcAddress");
        if (result.create_context_attribs == nullptr || result.destroy_context == nullptr ||
            result.make_current == nullptr || result.get_current_context == nullptr ||
            result.get_proc_address == nullptr) {
            throw ContextError("OSMesa context: " + lib.name() +
                               " lacks OSMesaCreateContextAttribs (Mesa >= 11.2 needed) or "
                               "another entry point. " +
                               kInstallHint);
        }
        return result;
    }();
    return api;
}

// For the error message when 4.5 core is refused: what does a default context offer?
std::string ProbeDefaultContext(const OsMesaApi& api) {
    const std::array<int, 3> attribs = {OSMESA_FORMAT, OSMESA_RGBA, 0};
    OSMesaContext context = api.create_context_attribs(attribs.data(), nullptr);
    if (context == nullptr) return "no context of any version could be created";
    std::vector<unsigned char> buffer(4 * kBufferSize * kBufferSize);
    std::string result = "a default context could not be made current";
    if (api.make_current(context, buffer.data(), GL_UNSIGNED_BYTE, kBufferSize, kBufferSize)) {
        using GetStringFn = const GLubyte* (*)(GLenum);
        auto get_string = reinterpret_cast<GetStringFn>(api.get_proc_address("glGetString"));
        const GLubyte* version = get_string != nullptr ? get_string(GL_VERSION) : nullptr;
        const GLubyte* renderer = get_string != nullptr ? get_string(GL_RENDERER) : nullptr;
        if (version != nullptr && renderer != nullptr) {
            result = std::string("a default context offers OpenGL ") +
                     reinterpret_cast<const char*>(version) + " on " +
                     reinterpret_cast<const char*>(renderer);
        }
        api.make_current(nullptr, nullptr, 0, 0, 0);
    }
    api.destroy_context(context);
    return result;
}

class OsMesaContext final : public HeadlessContext {
  public:
    OsMesaContext(const OsMesaApi& api, OSMesaContext context)
        : HeadlessContext(ContextKind::kOsMesa, "OSMesa (" + api.library.name() + ")"),
          api_(api),
          context_(context),
          buffer_(4 * kBufferSize * kBufferSize) {}

    ~OsMesaContext() override {
        if (api_.get_current_context() == context_) api_.make_current(nullptr, nullptr, 0, 0, 0);
        api_.destroy_context(context_);
    }

    GetProcAddressFn get_proc_address() const override { return api_.get_proc_address; }

    using HeadlessContext::Initialize;

  protected:
    void ReleaseCurrentImpl() override { api_.make_current(nullptr, nullptr, 0, 0, 0); }

    void MakeCurrentImpl() override {
        if (!api_.make_current(context_, buffer_.data(), GL_UNSIGNED_BYTE, kBufferSize,
                               kBufferSize)) {
            throw ContextError("OSMesa context: OSMesaMakeCurrent failed");
        }
    }

  private:
    const OsMesaApi& api_;
    OSMesaContext context_;
    std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<HeadlessContext> CreateOsMesaContext(const ContextOptions& options) {
    const OsMesaApi& api = Api();
    // Attribute lists as key, value rows.
    // clang-format off
    const std::array<int, 15> attribs = {
        OSMESA_FORMAT,                OSMESA_RGBA,
        OSMESA_DEPTH_BITS,            0,
        OSMESA_STENCIL_BITS,          0,
        OSMESA_ACCUM_BITS,            0,
        OSMESA_PROFILE,               OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, options.version.major,
        OSMESA_CONTEXT_MINOR_VERSION, options.version.minor,
        0,
    };
    // clang-format on
    OSMesaContext context = api.create_context_attribs(attribs.data(), nullptr);
    if (context == nullptr) {
        throw ContextError("OSMesa context: " + api.library.name() + " refused an OpenGL " +
                           std::to_string(options.version.major) + "." +
                           std::to_string(options.version.minor) + " core context; " +
                           ProbeDefaultContext(api) +
                           ". llvmpipe (Mesa >= 20) provides 4.5 core: check that GALLIUM_DRIVER "
                           "is unset or 'llvmpipe', or set ZENITH_GL=egl.");
    }
    auto result = std::make_unique<OsMesaContext>(api, context);
    result->Initialize(options.version);
    return result;
}

}  // namespace zenith::sky::gl::internal
