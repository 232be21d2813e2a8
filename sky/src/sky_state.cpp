#include "zenith/sky/sky_state.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <optional>

#include "zenith/base/error.h"
#include "zenith/base/units.h"
#include "zenith/geo/earth_orientation.h"
#include "zenith/geo/eclipse.h"
#include "zenith/geo/moon.h"
#include "zenith/geo/planets.h"
#include "zenith/geo/stars.h"
#include "zenith/geo/sun.h"
#include "zenith/sky/lighting.h"

namespace zenith::sky {
namespace {

// Mean B-V colour indices of the planets (Allen's Astrophysical Quantities, 4th ed., Table 12.x
// "Photometry of the planets"), in geo::Planet order; the Earth's entry is unused.
constexpr std::array<double, 8> kPlanetBMinusV = {0.93, 0.82, 0.0, 1.36, 0.83, 1.04, 0.56, 0.41};

// The Earth's shadow across the Moon (MoonDisk::Shadow): the sunlight reaching points of the
// Moon at distances from the shadow's axis spanning its disk, each at the Moon's centre's
// distance along the axis (the disk faces the Earth, 0.5-1.5 deg from the axis during an
// eclipse). Straight rays pass above the air only (shadow radius: the solid Earth plus the
// air), at every sample: they rise from 0 at the umbra's edge as a power 1.5 of the distance,
// a kink that 16 samples across the disk missed by up to 0.08 of the Sun's light (64: 0.015).
// The air's refracted light (UmbraRefractedLight, 0.15 ms a point), smooth across the disk, is
// worked out at kRefractedSamples and interpolated. None outside the penumbra.
std::optional<MoonDisk::Shadow> EarthShadowOnTheMoon(const geo::SkyEphemeris& e,
                                                     const Atmosphere& atmosphere) {
    const double shadow_radius =
        geo::kEarthShadowRadius + atmosphere.top_radius - atmosphere.bottom_radius;
    const geo::LunarEclipse centre = geo::ComputeLunarEclipse(e, shadow_radius);
    const double along = centre.moon_distance * std::cos(centre.axis_angle);
    const auto at = [&](double axis_distance) {
        const double distance = std::hypot(along, axis_distance);
        return geo::LunarEclipseAt(distance, glm::pi<double>() - std::atan2(axis_distance, along),
                                   e.sun.geocentric_distance, shadow_radius);
    };
    MoonDisk::Shadow shadow;
    shadow.axis_min_m = std::max(centre.axis_distance - geo::kMoonRadius, 0.0);
    shadow.axis_max_m = centre.axis_distance + geo::kMoonRadius;
    if (at(shadow.axis_min_m).direct_sunlight == glm::dvec3(1.0)) return std::nullopt;
    const auto axis_distance = [&](double f) {
        return shadow.axis_min_m + (shadow.axis_max_m - shadow.axis_min_m) * f;
    };
    constexpr int kRefractedSamples = 16;
    std::array<glm::dvec3, kRefractedSamples> refracted;
    for (int k = 0; k < kRefractedSamples; ++k) {
        const double x = axis_distance(static_cast<double>(k) / (kRefractedSamples - 1));
        const geo::LunarEclipse point = at(x);
        refracted[static_cast<std::size_t>(k)] =
            UmbraRefractedLight(atmosphere, x, point.moon_distance, point.sun_radius);
    }
    for (int i = 0; i < MoonDisk::kShadowSamples; ++i) {
        const double f = static_cast<double>(i) / (MoonDisk::kShadowSamples - 1);
        const double g = f * (kRefractedSamples - 1);
        const std::size_t k =
            std::min(static_cast<std::size_t>(g), static_cast<std::size_t>(kRefractedSamples - 2));
        shadow.sunlight[static_cast<std::size_t>(i)] =
            at(axis_distance(f)).direct_sunlight +
            glm::mix(refracted[k], refracted[k + 1], g - static_cast<double>(k));
    }
    return shadow;
}

// The sunlight reaching the Moon's face seen from the Earth, averaged over it weighted as a full
// Moon's Lambertian face is bright (the cosine of the angle from the disk's centre, as the Sun
// lies behind the Earth in an eclipse): a 32 x 32 grid over the disk.
glm::dvec3 MeanSunlightOnTheMoon(const MoonDisk::Shadow& shadow) {
    const double axis = shadow.axis_max_m - geo::kMoonRadius;  // the centre's (the table's span)
    constexpr int kGrid = 32;
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (int j = 0; j < kGrid; ++j) {
        for (int i = 0; i < kGrid; ++i) {
            const double u = 2.0 * (i + 0.5) / kGrid - 1.0, v = 2.0 * (j + 0.5) / kGrid - 1.0;
            if (u * u + v * v >= 1.0) continue;
            const double w = std::sqrt(1.0 - u * u - v * v);
            sum += w * ShadowSunlight(
                           shadow, std::hypot(axis + u * geo::kMoonRadius, v * geo::kMoonRadius));
            weights += w;
        }
    }
    return sum / weights;
}

}  // namespace

glm::dvec3 ShadowSunlight(const MoonDisk::Shadow& shadow, double axis_distance) {
    const double span = shadow.axis_max_m - shadow.axis_min_m;
    const double f =
        std::clamp(span > 0.0 ? (axis_distance - shadow.axis_min_m) / span : 0.0, 0.0, 1.0) *
        (MoonDisk::kShadowSamples - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(f),
                                   static_cast<std::size_t>(MoonDisk::kShadowSamples - 2));
    const double t = f - static_cast<double>(i);
    return glm::mix(shadow.sunlight[i], shadow.sunlight[i + 1], t);
}

glm::dvec3 PlanetIlluminance(const geo::PlanetPosition& planet) {
    return geo::IlluminanceFromMagnitude(planet.magnitude_v) *
           StarColour(kPlanetBMinusV[static_cast<std::size_t>(planet.planet)]);
}

glm::dvec3 StarColour(double b_minus_v) {
    // Steps of 0.01 from -0.40 to 4.00 (the catalogue's resolution and
    // geo::ColourFromBMinusV's clamp), computed once: the black-body integral costs ~4 us a call.
    static const std::array<glm::dvec3, 441> table = [] {
        std::array<glm::dvec3, 441> t{};
        for (std::size_t i = 0; i < t.size(); ++i) {
            t[i] = geo::ColourFromBMinusV(-0.40 + 0.01 * static_cast<double>(i));
        }
        return t;
    }();
    const double index = std::round((b_minus_v + 0.40) / 0.01);
    return table[static_cast<std::size_t>(std::clamp(index, 0.0, 440.0))];
}

double LambertSphereIlluminanceFactor(double albedo, double phase_angle, double angular_radius) {
    // Integral of A cos(i) / pi over the visible lit part of a Lambertian sphere:
    // (2/3) A sin^2(angular radius) Phi(alpha), Phi = (sin a + (pi - a) cos a) / pi.
    const double a = std::clamp(phase_angle, 0.0, glm::pi<double>());
    const double phi = (std::sin(a) + (glm::pi<double>() - a) * std::cos(a)) / glm::pi<double>();
    const double s = std::sin(angular_radius);
    return 2.0 / 3.0 * albedo * s * s * phi;
}

SkyState MakeSkyState(const geo::SkyEphemeris& e, const geo::Observer& observer,
                      const Atmosphere& atmosphere, const geo::Attitude& attitude,
                      double vertical_fov, double aspect, const geo::RefractionTable* refraction) {
    SkyState state;
    Camera& camera = state.view.camera;
    camera.position = glm::dvec3(0.0, 0.0, atmosphere.bottom_radius + observer.height_m());
    camera.world_from_view = geo::EnuFromView(attitude);
    camera.vertical_fov = vertical_fov;
    camera.aspect = aspect;
    state.sun_elevation = e.sun.topocentric.horizontal.elevation;

    SkyScene& s = state.scene;

    const double sun_distance_au = e.sun.topocentric.horizontal.distance / geo::kAstronomicalUnit;
    s.lights.sun_direction = e.sun.topocentric.horizontal.direction_enu;
    s.lights.sun_illuminance = atmosphere.solar_illuminance / (sun_distance_au * sun_distance_au);

    s.moon.enabled = true;
    s.moon.direction = e.moon.topocentric.horizontal.direction_enu;
    s.moon.angular_radius = 0.5 * e.moon.angular_diameter;
    s.moon.distance_m = e.moon.topocentric.horizontal.distance;
    s.lights.moon_enabled = true;
    s.lights.moon_direction = s.moon.direction;
    if (refraction) {
        const auto place = [&](const glm::dvec3& direction) {
            return ApparentPlace{ApparentDirection(*refraction, direction),
                                 refraction->VerticalScale(std::asin(direction.z))};
        };
        s.sun_apparent = place(s.lights.sun_direction);
        s.moon.apparent = place(s.moon.direction);
    }
    s.lights.moon_illuminance = s.lights.sun_illuminance *
                                LambertSphereIlluminanceFactor(
                                    s.moon.albedo, e.moon_phase.phase_angle, s.moon.angular_radius);

    // The night sky's frames: world (the observer's ENU) to TOD through ECEF, then to the
    // ecliptic of date and to ICRS (precession-nutation undone; polar motion is ignored).
    const glm::dmat3 tod_from_world =
        glm::transpose(geo::EcefFromTod(e.time)) * observer.ecef_from_enu();
    s.night_sky.enabled = true;
    s.night_sky.ecliptic_from_world =
        glm::transpose(geo::TodFromEclipticOfDate(e.time.jd_tt)) * tod_from_world;
    s.night_sky.icrs_from_world = glm::transpose(geo::TodFromGcrs(e.time.jd_tt)) * tod_from_world;
    s.night_sky.sun_ecliptic_longitude = geo::SunApparentEcliptic(e.time.jd_tt).longitude;

    // A solar eclipse: the camera's sunlight is what the Moon leaves of the limb-darkened disk;
    // the air elsewhere gets its own share and the disk pass draws the crescent (Lights).
    const geo::SolarEclipse solar = geo::ComputeSolarEclipse(e);
    if (solar.partial()) {
        Lights::SolarEclipse& eclipse = s.lights.eclipse;
        eclipse.active = true;
        eclipse.unobscured_illuminance = s.lights.sun_illuminance;
        eclipse.moon_position =
            camera.position + e.moon.topocentric.horizontal.distance * s.moon.direction;
        eclipse.sun_angular_radius = solar.sun_radius;
        eclipse.moon_angular_radius = solar.moon_radius;
        eclipse.limb_ratio = EclipseLimbTable(solar.moon_radius / solar.sun_radius);
        s.lights.sun_illuminance *= solar.uncovered_flux;
        eclipse.around_illuminance =
            EclipseAroundIlluminance(atmosphere, s.lights, camera.position);
    }
    // A lunar eclipse: the Sun's light reaching the Moon past the Earth and its air in straight
    // lines, plus what the air refracts and filters into the shadow, across the disk (computed
    // only while a part of the Moon is in the penumbra).
    if (std::optional<MoonDisk::Shadow> shadow = EarthShadowOnTheMoon(e, atmosphere)) {
        s.moon.sunlight = MeanSunlightOnTheMoon(*shadow);
        s.moon.shadow = *shadow;
        s.lights.moon_illuminance *= s.moon.sunlight;
    }

    const auto seen = [&](const glm::dvec3& direction) {
        return refraction ? ApparentDirection(*refraction, direction) : direction;
    };
    s.stars.reserve(e.stars.size());
    for (const geo::StarState& star : e.stars) {
        s.stars.push_back({seen(star.horizontal.direction_enu),
                           star.illuminance_lux * StarColour(star.star->b_minus_v)});
    }
    // Planets are drawn like stars, their magnitude as illuminance and their colour from B-V;
    // a disk wider than a pixel (at most Venus's 66", in a narrow field of view) as a sphere lit
    // from the Sun's side (ResolveDisks).
    const double min_elevation = MinStarElevation(atmosphere.bottom_radius, observer.height_m());
    const glm::dvec3 sun =
        e.sun.topocentric.horizontal.direction_enu * e.sun.topocentric.horizontal.distance;
    for (const geo::PlanetPosition& planet : e.planets) {
        if (planet.topocentric.horizontal.elevation < min_elevation) continue;
        const glm::dvec3 toward = planet.topocentric.horizontal.direction_enu;
        StarPoint point{seen(toward), PlanetIlluminance(planet)};
        point.angular_radius =
            0.5 * planet.angular_diameter_arcsec * (glm::pi<double>() / 648000.0);
        point.sunward =
            glm::normalize(sun - toward * (planet.distance_au * geo::kAstronomicalUnit));
        s.stars.push_back(point);
    }
    return state;
}

glm::dvec3 ApparentDirection(const geo::RefractionTable& refraction, const glm::dvec3& direction) {
    const double horizontal = std::hypot(direction.x, direction.y);
    const std::optional<double> apparent =
        refraction.Apparent(std::asin(std::clamp(direction.z, -1.0, 1.0)));
    if (!apparent || horizontal < 1e-12) return direction;
    const double scale = std::cos(*apparent) / horizontal;
    return {direction.x * scale, direction.y * scale, std::sin(*apparent)};
}

const geo::RefractionTable& RefractionCache::Get(const geo::RefractionAir& air, double height_m,
                                                 double planet_radius_m) {
    // The dip sqrt(2 h / R) moves by dh / sqrt(2 h R): 5" (2.4e-5 rad) or 0.5 m.
    const double tolerance =
        std::max(0.5, 2.4e-5 * std::sqrt(2.0 * std::max(height_m, 0.0) * planet_radius_m));
    if (!table_ || !(table_->air() == air) || table_->planet_radius_m() != planet_radius_m ||
        std::abs(table_->height_m() - height_m) > tolerance) {
        table_.emplace(air, height_m, planet_radius_m);
    }
    return *table_;
}

double MinStarElevation(double bottom_radius, double height_m) {
    const double dip = std::acos(bottom_radius / (bottom_radius + std::max(height_m, 0.0)));
    return -(dip + Radians(0.6));
}

void ValidateProjection(double vertical_fov, double aspect) {
    Require("fov_deg", Degrees(vertical_fov), "deg", Range::Open(0.0, 180.0));
    Require("aspect", aspect, "", Range::Open(0.0, 1e6));
}

SkyFrame BuildSkyFrame(const geo::Ephemeris& calculator, const FrameSetup& setup,
                       const Atmosphere& atmosphere, RefractionCache* cache) {
    setup.Validate();
    SkyFrame frame;
    geo::EphemerisOptions options;
    options.star_min_elevation =
        MinStarElevation(atmosphere.bottom_radius, setup.observer.height_m());
    frame.ephemeris = calculator.Compute(setup.time, setup.observer, options);
    std::optional<geo::RefractionTable> own;
    const geo::RefractionTable* refraction = nullptr;
    if (setup.refraction) {
        const double height = setup.observer.height_m();
        refraction = cache ? &cache->Get(*setup.refraction, height, atmosphere.bottom_radius)
                           : &own.emplace(*setup.refraction, height, atmosphere.bottom_radius);
    }
    static_cast<SkyState&>(frame) =
        MakeSkyState(frame.ephemeris, setup.observer, atmosphere, setup.attitude,
                     setup.vertical_fov, setup.aspect, refraction);
    if (setup.enu_from_view) frame.view.camera.world_from_view = *setup.enu_from_view;
    return frame;
}

glm::dmat3 WeatherFrame(const geo::Observer& observer, double origin_lat_deg,
                        double origin_lon_deg) {
    const glm::dmat3 origin = geo::Observer(origin_lat_deg, origin_lon_deg, 0.0).ecef_from_enu();
    return glm::transpose(origin) * observer.ecef_from_enu();
}

}  // namespace zenith::sky
