#include "zenith/sky/gl/context.h"

#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "gl/backends.h"
#include "zenith/base/error.h"

namespace zenith::sky::gl {
namespace {

std::string_view GetEnv(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr ? std::string_view(value) : std::string_view();
}

// The HeadlessContext current on this thread, if zenith made it current.
thread_local HeadlessContext* g_current = nullptr;

}  // namespace

ContextKind ParseContextKind(std::string_view name) {
    if (name == "osmesa") return ContextKind::kOsMesa;
    if (name == "egl") return ContextKind::kEgl;
    throw ArgumentError("unknown GL context kind '" + std::string(name) +
                        "': expected 'osmesa' (default, headless llvmpipe) or 'egl'");
}

std::string_view ToString(ContextKind kind) {
    switch (kind) {
        case ContextKind::kOsMesa:
            return "osmesa";
        case ContextKind::kEgl:
            return "egl";
    }
    return "unknown";
}

ContextKind ContextKindFromEnvironment() {
    const std::string_view value = GetEnv("ZENITH_GL");
    if (value.empty()) return ContextKind::kOsMesa;
    try {
        return ParseContextKind(value);
    } catch (const ArgumentError& error) {
        throw ArgumentError(std::string("environment variable ZENITH_GL: ") + error.what());
    }
}

EglOptions ParseEglOptions(std::string_view text) {
    if (text == "auto") return {EglPlatform::kAuto, -1};
    if (text == "surfaceless") return {EglPlatform::kSurfaceless, -1};
    if (text == "device") return {EglPlatform::kDevice, -1};
    constexpr std::string_view kDevicePrefix = "device:";
    if (text.starts_with(kDevicePrefix)) {
        const std::string_view digits = text.substr(kDevicePrefix.size());
        int index = -1;
        const auto [end, error] =
            std::from_chars(digits.data(), digits.data() + digits.size(), index);
        if (error == std::errc() && end == digits.data() + digits.size() && !digits.empty() &&
            index >= 0) {
            return {EglPlatform::kDevice, index};
        }
    }
    throw ArgumentError("unknown EGL platform '" + std::string(text) +
                        "': expected 'auto', 'surfaceless', 'device' or 'device:N' "
                        "(N = EGL device index, 0 or more)");
}

EglOptions EglOptionsFromEnvironment() {
    const std::string_view value = GetEnv("ZENITH_EGL_PLATFORM");
    if (value.empty()) return {};
    try {
        return ParseEglOptions(value);
    } catch (const ArgumentError& error) {
        throw ArgumentError(std::string("environment variable ZENITH_EGL_PLATFORM: ") +
                            error.what());
    }
}

HeadlessContext::~HeadlessContext() {
    if (g_current == this) g_current = nullptr;
}

void HeadlessContext::MakeCurrent() {
    // OSMesa and EGL each track their own current context; leaving the other one current would
    // leave two libraries believing they own this thread's GL state.
    if (g_current != nullptr && g_current != this && g_current->kind() != kind()) {
        g_current->ReleaseCurrent();
    }
    MakeCurrentImpl();
    g_current = this;
    // GL pointers are process-wide; pointers from another library would dispatch to nothing.
    if (internal::LastLoader() != get_proc_address()) {
        info_ = LoadGlFunctions(get_proc_address(), required_);
    }
}

void HeadlessContext::ReleaseCurrent() {
    ReleaseCurrentImpl();
    if (g_current == this) g_current = nullptr;
}

void HeadlessContext::Initialize(GlVersion required) {
    required_ = required;
    const bool make_current_loads = internal::LastLoader() != get_proc_address();
    MakeCurrent();
    // Same library as the last context: the pointers are valid, but this context's version is
    // still to be checked.
    if (!make_current_loads) info_ = LoadGlFunctions(get_proc_address(), required_);
}

std::unique_ptr<HeadlessContext> CreateHeadlessContext(ContextKind kind) {
    ContextOptions options;
    options.kind = kind;
    return CreateHeadlessContext(options);
}

std::unique_ptr<HeadlessContext> CreateHeadlessContext(const ContextOptions& options) {
    switch (options.kind) {
        case ContextKind::kOsMesa:
            return internal::CreateOsMesaContext(options);
        case ContextKind::kEgl:
            return internal::CreateEglContext(options);
    }
    throw ArgumentError("CreateHeadlessContext: invalid ContextKind");
}

std::unique_ptr<HeadlessContext> CreateHeadlessContextFromEnvironment() {
    ContextOptions options;
    options.kind = ContextKindFromEnvironment();
    options.egl = EglOptionsFromEnvironment();
    return CreateHeadlessContext(options);
}

}  // namespace zenith::sky::gl
