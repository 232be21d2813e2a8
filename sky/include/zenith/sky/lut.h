// Look-up-table settings and images shared by the GL renderer and the CPU reference, plus the
// camera and light description both use. Frames: planet-centred, metres (SI); the planet's
// centre is the origin and the camera's "up" is its position's direction.
#pragma once

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::sky {

// LUT sizes and ray-marching step counts (Hillaire 2020, Table 2). Pc() is the paper's PC column,
// Mobile() its iPhone 6s column; every field may be changed.
struct LutSettings {
    glm::ivec2 transmittance_size{256, 64};
    int transmittance_steps = 40;
    // H20 §5.5.3 has 32 x 32 texels and 64 directions. Past sunset that is too coarse for the
    // orders and moments below: 32 texels in sqrt|mu_s| are ~2.3 deg of sun elevation apart at
    // 96 deg, where the twilight sky falls ~3x per degree, and 64 directions are ~25 deg apart,
    // wider than the bright sunward horizon that lights Earth's shadow. 128 texels and 256
    // directions meet issue 18's twilight goal (BENCHMARKS.md, "Twilight grid").
    glm::ivec2 multiple_scattering_size{128, 32};
    int multiple_scattering_directions_sqrt = 16;  // 16 x 16 = 256 directions
    int multiple_scattering_steps = 20;
    // Orders of scattering integrated one from another before H20's geometric series takes the
    // rest (ComputeScatteringOrderTexel in atmosphere/functions.glsl); 2 is H20's form, L_2 /
    // (1 - f_ms). Each order is one more pass over the multiple-scattering LUT, when the
    // atmosphere changes only; 3 meets the twilight goal, 2 leaves its blue p95 at 21 %.
    int multiple_scattering_orders = 3;
    // Layers of the plane-parallel column whose orders correct H20's series past order K where
    // the air is optically thick (sky/src/multiple_scattering_column.h); 0: the series alone.
    // With 128 the `thick` preset's correction is within 0.3 % (at the ground) to 2 % (50 km up)
    // of 512 layers'; the column is solved on the CPU when the atmosphere changes, 16-33 ms on
    // one core (about 4x per doubling).
    int multiple_scattering_column_layers = 128;
    // 256 (the paper has no such LUT): between texels it stays within 4 % of the exact integral
    // through twilight, where the sky's illuminance falls ~3x per degree of sun depression.
    glm::ivec2 irradiance_size{256, 1};
    int irradiance_directions_sqrt = 8;
    int irradiance_steps = 16;
    glm::ivec2 sky_view_size{200, 100};
    int sky_view_steps = 30;
    glm::ivec3 aerial_perspective_size{32, 32, 32};
    double aerial_perspective_range = 32000.0;  // m
    int aerial_perspective_steps = 30;          // for the full range; fewer for nearer slices

    // The multiple-scattering LUT's texture: its tiles (atmosphere/functions.glsl:
    // MultipleScatteringTexel) side by side, each multiple_scattering_size.
    glm::ivec2 multiple_scattering_texture_size() const;

    static LutSettings Pc() { return {}; }
    static LutSettings Mobile();
    // Throws zenith::ArgumentError naming the field, value and allowed range.
    void Validate() const;
};

// A LUT read back or computed on the CPU: RGBA float texels, x fastest, then y, then z.
struct LutImage {
    glm::ivec3 size{0, 0, 1};
    std::vector<glm::vec4> texels;

    LutImage() = default;
    LutImage(int width, int height, int depth = 1)
        : size(width, height, depth),
          texels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                 static_cast<std::size_t>(depth)) {}
    std::size_t Index(int x, int y, int z = 0) const {
        return (static_cast<std::size_t>(z) * static_cast<std::size_t>(size.y) +
                static_cast<std::size_t>(y)) *
                   static_cast<std::size_t>(size.x) +
               static_cast<std::size_t>(x);
    }
    glm::vec4& at(int x, int y, int z = 0) { return texels[Index(x, y, z)]; }
    const glm::vec4& at(int x, int y, int z = 0) const { return texels[Index(x, y, z)]; }
    std::size_t bytes() const { return texels.size() * sizeof(glm::vec4); }
};

// Directional lights: the Sun and, optionally, the Moon (H20's N_light = 2). Directions are unit
// vectors toward the light in the planet-centred frame; illuminances in lux at the top of the
// atmosphere, per RGB channel.
struct Lights {
    glm::dvec3 sun_direction{0.0, 0.0, 1.0};
    glm::dvec3 sun_illuminance{127000.0};
    bool moon_enabled = false;
    glm::dvec3 moon_direction{0.0, 0.0, 1.0};
    glm::dvec3 moon_illuminance{0.0};
    // A solar eclipse seen from the camera (MakeSkyState fills it from the ephemeris; inactive by
    // default, and then nothing below is used). sun_illuminance is then the light the Moon leaves
    // the camera (geo::SolarEclipse::uncovered_flux times the Sun's), for everything lit as a
    // whole (clouds, the host's SkyLighting). The LUTs' ray marches light each point of the air
    // by what the Moon leaves of the Sun there (the umbra and penumbra: a cone along the Sun's
    // direction through the Moon's centre, uniform disks), from unobscured_illuminance, so the
    // air outside the umbra stays sunlit; the disk pass draws the uncovered part of the Sun's
    // disk at its unobscured luminance and the corona around it.
    struct SolarEclipse {
        bool active = false;
        glm::dvec3 unobscured_illuminance{0.0};  // lux per channel, top of the atmosphere
        glm::dvec3 moon_position{0.0};           // m, planet-centred: the Moon's centre
        double sun_angular_radius = 0.0;         // rad, seen from the camera
        double moon_angular_radius = 0.0;        // rad, seen from the camera
        // The Sun's illuminance behind the light multiply scattered around the camera
        // (EclipseAroundIlluminance; LightSet.eclipse_around_illuminance): what lights the
        // umbra's air from the sunlit air beyond it. 0: none.
        glm::dvec3 around_illuminance{0.0};
        // The limb darkening's ratio of light to area left at 8 separations (EclipseLimbTable;
        // LightSet.eclipse_limb in sky/shaders/atmosphere/functions.glsl). All 1: uniform disks.
        std::array<glm::dvec3, 8> limb_ratio = {glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0),
                                                glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0),
                                                glm::dvec3(1.0), glm::dvec3(1.0)};
    } eclipse;
};

// Where the air's refraction shows a disk (MakeSkyState, from geo::RefractionTable): its
// centre's apparent direction, and how much refraction squeezes it vertically (the vertical
// scale, d apparent / d geometric elevation: ~0.8 for the Sun on a sea-level horizon). The disk
// is lit, phased and eclipsed in its geometric direction and drawn here.
struct ApparentPlace {
    glm::dvec3 direction{0.0, 0.0, 1.0};  // unit
    double vertical_scale = 1.0;
};

// The Moon drawn as a Lambertian sphere lit by the Sun (its phase and bright limb follow).
struct MoonDisk {
    bool enabled = false;
    glm::dvec3 direction{0.0, 0.0, 1.0};  // unit, toward the Moon's centre
    double angular_radius = 0.0045;       // rad
    double albedo = 0.12;                 // Lambertian reflectance (the Moon's mean albedo)
    // Fraction of the Sun's light (per channel) reaching the Moon: < 1 in a lunar eclipse, the
    // sunlight past the Earth's disk plus what the air refracts into the umbra (MakeSkyState),
    // the mean over the disk. Drawn so where there is no `shadow`.
    glm::dvec3 sunlight{1.0};
    std::optional<ApparentPlace> apparent;  // none: drawn in `direction`
    // In a lunar eclipse, the Earth's shadow across the disk: the sunlight reaching a point of
    // the Moon at kShadowSamples distances from the shadow's axis (the Earth-Sun line), evenly
    // from axis_min_m to axis_max_m (the disk's nearest and farthest), interpolated in between.
    // `distance_m` places the disk's points (from the camera).
    static constexpr int kShadowSamples = 64;
    struct Shadow {
        double axis_min_m = 0.0;
        double axis_max_m = 0.0;
        std::array<glm::dvec3, kShadowSamples> sunlight{};
    };
    std::optional<Shadow> shadow;
    double distance_m = 3.844e8;
};

// A point source: a star, a planet, or the Sun when its disk is smaller than a pixel. A
// planet's disk wider than a pixel is drawn as a disk (ResolveDisks).
struct StarPoint {
    glm::dvec3 direction{0.0, 0.0, 1.0};  // unit
    glm::dvec3 illuminance{0.0};          // lux per channel at the top of the atmosphere
    double angular_radius = 0.0;          // rad: a planet's disk; 0: a point
    glm::dvec3 sunward{0.0};              // unit, from the body toward the Sun; 0: evenly lit
};

// The points with each disk wider than `pixel` (rad, the angle of a pixel) spread over it: a
// Lambertian sphere lit from `sunward` (its phase: Venus' crescent), sampled at least twice a
// pixel across; the disk's illuminance is kept (its magnitude already has the phase). Each
// sample keeps its disk's angular_radius and sunward.
std::vector<StarPoint> ResolveDisks(const std::vector<StarPoint>& points, double pixel);

// A pinhole camera, OpenGL convention: it looks along -z of its view frame, +y up, +x right.
struct Camera {
    glm::dvec3 position{0.0, 0.0, 6360e3 + 1.0};  // m, planet-centred
    glm::dmat3 world_from_view{1.0};              // columns: right, up, backward
    double vertical_fov = 1.0471975511965976;     // rad (60 deg)
    double aspect = 16.0 / 9.0;                   // width / height

    // World direction through normalised device coordinates (x, y) in [-1, 1].
    glm::dvec3 Direction(double ndc_x, double ndc_y) const {
        const double t = std::tan(0.5 * vertical_fov);
        return glm::normalize(world_from_view * glm::dvec3(ndc_x * t * aspect, ndc_y * t, -1.0));
    }
};

}  // namespace zenith::sky
