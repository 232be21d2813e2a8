// A host that loads GL with its own glad (generated into this build, see CMakeLists.txt) and
// attaches zenith to its context: zenith's loader must neither clash with the host's glad at link
// time nor share its function pointers at run time. One frame is drawn into the host's
// framebuffer, made and read back with the host's own GL 3.3 functions.
#include <glad/gl.h>  // the host's glad, first: it refuses to follow another GL header

#include <cmath>
#include <cstdio>
#include <exception>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "zenith/sim/sky_system.h"
#include "zenith/sky/gl/context.h"

namespace {

// The host wraps one of its own pointers to see whether zenith calls through it.
PFNGLUSEPROGRAMPROC g_host_use_program = nullptr;
int g_host_use_program_calls = 0;
void GLAD_API_PTR CountingUseProgram(GLuint program) {
    ++g_host_use_program_calls;
    g_host_use_program(program);
}

void Check(bool ok, const std::string& what) {
    if (!ok) throw std::runtime_error(what);
}

}  // namespace

int main() try {
    using namespace zenith;
    constexpr int kWidth = 160, kHeight = 90;

    // The host's context (a window's, in a real host). Making it loads zenith's GL functions.
    const auto context = sky::gl::CreateHeadlessContextFromEnvironment();
    Check(glad_glClear == nullptr,
          "zenith's loader filled the host's glad pointers (glad_glClear) before the host loaded");

    // The host's own loader, for its own use.
    const int version = gladLoadGL(context->get_proc_address());
    Check(version >= GLAD_MAKE_VERSION(3, 3), "the host's gladLoadGL failed");
    g_host_use_program = glad_glUseProgram;
    glad_glUseProgram = &CountingUseProgram;

    auto sky = sim::SkySystem::CreateInHostContext(context->get_proc_address());
    sky->SetTime(geo::TimeFromIso8601("2024-06-21T10:00:00Z"));
    sky->SetProjection(glm::radians(60.0), double(kWidth) / kHeight);
    sky->SetGeodetic(47.0, 8.5, 3000.0);
    sky->SetAttitude(glm::radians(135.0), glm::radians(10.0), 0.0);  // south-east, a little up

    // The host's render target, made with GL 3.3 calls through its own glad.
    GLuint colour = 0, framebuffer = 0;
    glGenTextures(1, &colour);
    glBindTexture(GL_TEXTURE_2D, colour);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kWidth, kHeight, 0, GL_RGBA, GL_FLOAT, nullptr);
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
    Check(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
          "the host's framebuffer is incomplete");
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    sky->Update();
    sky->Render(framebuffer, {0, 0, kWidth, kHeight});

    std::vector<float> pixels(static_cast<std::size_t>(kWidth) * kHeight * 4);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, pixels.data());
    Check(glGetError() == GL_NO_ERROR, "GL error after the frame");
    double sum = 0.0;
    for (std::size_t i = 0; i < pixels.size(); i += 4) sum += pixels[i + 1];
    const double mean_green = sum / (static_cast<double>(kWidth) * kHeight);
    Check(std::isfinite(mean_green) && mean_green > 100.0,
          "the frame has no daylight sky: mean G " + std::to_string(mean_green) + " cd/m^2");
    Check(g_host_use_program_calls == 0, "zenith called the host's glad pointers (glUseProgram " +
                                             std::to_string(g_host_use_program_calls) + " times)");

    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &colour);
    std::printf("host glad " HOST_GLAD_API
                " (context %d.%d) and zenith: one frame, mean G %.0f cd/m^2\n",
                GLAD_VERSION_MAJOR(version), GLAD_VERSION_MINOR(version), mean_green);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "host_glad: %s\n", e.what());
    return 1;
}
