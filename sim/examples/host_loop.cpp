// A host's simulation loop with zenith attached — copy this shape into your simulator.
//
// Physics runs at a fixed 100 Hz; the sky is updated and drawn at 25 Hz into the host's own
// framebuffer object; the host reads back the lighting for its own shading. Time runs at 60x
// (an hour of sky per simulated minute). It is built the way a host is: the GL context is the
// host's (here a headless one from zenith's installed context helper, standing in for a GLFW or
// SDL window), zenith is attached with SkySystem::CreateInHostContext(getProcAddress), and the
// host reaches GL through its own loader (here a handful of pointers through the same
// getProcAddress; a real host has glad, GLEW or epoxy). It needs only the installed package and
// the Khronos <GL/glcorearb.h> (Debian: libgl-dev / mesa-common-dev); the package test builds it.
//
//   zenith-example-host [simulated seconds = 60] [output.png]
#include <GL/glcorearb.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <glm/gtc/constants.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "zenith/sim/sky_system.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/image_io.h"

namespace {

// The host's own GL entry points (its loader), for the context current on this thread.
struct HostGl {
    PFNGLCREATETEXTURESPROC CreateTextures;
    PFNGLTEXTURESTORAGE2DPROC TextureStorage2D;
    PFNGLCREATEFRAMEBUFFERSPROC CreateFramebuffers;
    PFNGLNAMEDFRAMEBUFFERTEXTUREPROC NamedFramebufferTexture;
    PFNGLGETTEXTUREIMAGEPROC GetTextureImage;
    PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers;
    PFNGLDELETETEXTURESPROC DeleteTextures;

    explicit HostGl(zenith::sim::GetProcAddressFn get_proc_address)
        : CreateTextures(Load<PFNGLCREATETEXTURESPROC>(get_proc_address, "glCreateTextures")),
          TextureStorage2D(Load<PFNGLTEXTURESTORAGE2DPROC>(get_proc_address, "glTextureStorage2D")),
          CreateFramebuffers(
              Load<PFNGLCREATEFRAMEBUFFERSPROC>(get_proc_address, "glCreateFramebuffers")),
          NamedFramebufferTexture(Load<PFNGLNAMEDFRAMEBUFFERTEXTUREPROC>(
              get_proc_address, "glNamedFramebufferTexture")),
          GetTextureImage(Load<PFNGLGETTEXTUREIMAGEPROC>(get_proc_address, "glGetTextureImage")),
          DeleteFramebuffers(
              Load<PFNGLDELETEFRAMEBUFFERSPROC>(get_proc_address, "glDeleteFramebuffers")),
          DeleteTextures(Load<PFNGLDELETETEXTURESPROC>(get_proc_address, "glDeleteTextures")) {}

    template <class Fn>
    static Fn Load(zenith::sim::GetProcAddressFn get_proc_address, const char* name) {
        const zenith::sky::gl::GlProc proc = get_proc_address(name);
        if (proc == nullptr) throw std::runtime_error(std::string("no GL function ") + name);
        return reinterpret_cast<Fn>(proc);
    }
};

// The host's aircraft: a level turn at 10 km around a point near Zurich, 230 m/s.
struct Aircraft {
    double lat_deg = 47.0, lon_deg = 8.5, height_m = 10000.0, heading = 0.0;
    void Step(double dt) {
        constexpr double kSpeed = 230.0, kTurnRate = 0.01;  // m/s, rad/s
        heading += kTurnRate * dt;
        const double north = kSpeed * dt * std::cos(heading),
                     east = kSpeed * dt * std::sin(heading);
        lat_deg += glm::degrees(north / 6371000.0);
        lon_deg += glm::degrees(east / (6371000.0 * std::cos(glm::radians(lat_deg))));
    }
};

}  // namespace

int main(int argc, char** argv) try {
    using namespace zenith;
    const double duration_s = argc > 1 ? std::atof(argv[1]) : 60.0;
    const char* out = argc > 2 ? argv[2] : "host_loop.png";
    constexpr double kPhysicsDt = 0.01;  // 100 Hz
    constexpr double kFrameDt = 0.04;    // 25 Hz
    constexpr double kTimeWarp = 60.0;
    constexpr int kWidth = 640, kHeight = 360;

    // The host's context, current on this thread (a window's, in a real host), and its loader.
    const auto context = sky::gl::CreateHeadlessContextFromEnvironment();
    const HostGl gl(context->get_proc_address());
    sim::SkySystemSettings settings;
    settings.environment.size = 32;  // the sky around the aircraft for its reflections and
                                     // diffuse light on any normal (SkyIrradianceEnu)
    auto sky = sim::SkySystem::CreateInHostContext(context->get_proc_address(), settings);
    sky->SetTime(geo::TimeFromIso8601("2024-06-21T18:30:00Z"));  // the sun sets during the run
    sky->SetProjection(glm::radians(60.0), double(kWidth) / kHeight);

    // The host's render target (its own FBO; the sky is drawn as linear luminance, cd/m^2).
    GLuint colour = 0, framebuffer = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &colour);
    gl.TextureStorage2D(colour, 1, GL_RGBA32F, kWidth, kHeight);
    gl.CreateFramebuffers(1, &framebuffer);
    gl.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);

    Aircraft aircraft;
    // Warm-up: the GL driver's first-use work and a whole round of the environment's faces, so
    // the first frame costs what any frame costs and has the sky's harmonics.
    sky->SetGeodetic(aircraft.lat_deg, aircraft.lon_deg, aircraft.height_m);
    sky->Prepare({kWidth, kHeight});
    double physics_time = 0.0, next_frame = 0.0, next_report = 0.0;
    int frames = 0;
    while (physics_time < duration_s) {
        aircraft.Step(kPhysicsDt);  // the host's fixed-step physics
        physics_time += kPhysicsDt;
        sky->AdvanceTime(kPhysicsDt, kTimeWarp);
        if (physics_time < next_frame) continue;
        next_frame += kFrameDt;

        sky->SetGeodetic(aircraft.lat_deg, aircraft.lon_deg, aircraft.height_m);
        sky->SetAttitude(aircraft.heading, 0.0, glm::radians(25.0));  // banked in the turn
        sky->Update();
        sky->Render(framebuffer, {0, 0, kWidth, kHeight});
        ++frames;

        const sim::SkyLighting& light = sky->lighting();  // for the host's own shading
        if (physics_time >= next_report) {
            next_report += 10.0;
            const geo::CivilTime civil = geo::CivilFromJulianDate(sky->time().jd_utc);
            // The sky's light on the aircraft's belly (facing down: the ground and the haze
            // below), from the environment's harmonics once a round of its faces is done.
            const double belly = light.SkyIrradianceEnu({0.0, 0.0, -1.0}).y;
            std::printf("%s  sun %6.2f deg  %-21s  sun %8.0f lux  sky %7.0f lux  belly %7.0f lux\n",
                        geo::FormatIso8601(civil).c_str(), glm::degrees(light.sun_elevation),
                        sim::ToString(light.phase), light.sun_illuminance.y, light.sky_irradiance.y,
                        belly);
        }
    }

    // The last frame, exposed for viewing.
    sky::Image image(kWidth, kHeight);
    std::vector<glm::vec4> pixels(static_cast<std::size_t>(kWidth) * kHeight);
    gl.GetTextureImage(colour, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels.size() * 16),
                       pixels.data());
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            image.at(x, y) = pixels[static_cast<std::size_t>((kHeight - 1 - y) * kWidth + x)];
        }
    }
    sky::WriteImage(out, image, {});
    std::printf("%d frames; last frame in %s\n", frames, out);
    gl.DeleteFramebuffers(1, &framebuffer);
    gl.DeleteTextures(1, &colour);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "zenith-example-host: %s\n", e.what());
    return 1;
}
