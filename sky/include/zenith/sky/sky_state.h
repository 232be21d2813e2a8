// From where things are (geo) to what the renderer draws: the scene (lights, Moon disk, stars)
// and the view (camera) in the atmosphere's planet-centred frame. BuildSkyFrame is the one
// frame builder: SkySystem, `zenith render` (sim::RenderFrame), zenith-plot and the golden frames
// all make their frames with it.
//
// How the spherical planet meets the WGS84 ellipsoid: the frame's axes are the observer's local
// east/north/up (up = the ellipsoid normal, as geo/ reports elevations), the sphere's centre lies
// bottom_radius + height below the camera along that normal, and height is the geodetic height
// above the ellipsoid. So the ground under the aircraft is at exactly its ellipsoidal height, the
// zenith and the horizon plane are geo/'s, and the only approximation is the curvature of distant
// ground (the sphere's radius instead of the ellipsoid's local radii, 6335-6400 km for Earth):
// the horizon dip from 10 km differs by < 0.5 % (0.016 deg). Placing the camera at its
// geocentric radius instead would misplace the ground by up to 21 km.
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "zenith/geo/ephemeris.h"
#include "zenith/geo/frames.h"
#include "zenith/geo/observer.h"
#include "zenith/geo/refraction.h"
#include "zenith/geo/time.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/frame.h"

namespace zenith::sky {

struct SkyState {
    SkyScene scene;  // its CloudView is the identity: the weather map's origin under the camera
    SkyView view;
    double sun_elevation = 0.0;  // rad, geometric, for exposure and day/night decisions
};

// The colour (RGB of unit luminance) of a star of colour index B-V, a black body's
// (geo::ColourFromBMinusV) in steps of 0.01 mag, cached.
glm::dvec3 StarColour(double b_minus_v);

// A planet's light at the top of the atmosphere (lux, RGB): its V magnitude as illuminance, its
// colour from its mean B-V (Allen's Astrophysical Quantities). What the renderer draws it with.
glm::dvec3 PlanetIlluminance(const geo::PlanetPosition& planet);

// Lambertian sphere of `albedo` at phase angle `phase_angle` (rad): the illuminance it sends to
// the observer per unit solar illuminance, times the solid angle it subtends (Moon as a light).
double LambertSphereIlluminanceFactor(double albedo, double phase_angle, double angular_radius);

// The rotation from the renderer's frame at `observer` (its ENU axes) to the weather frame of
// a weather map whose origin is at (origin_lat_deg, origin_lon_deg): ENU axes there, so the map's
// x runs east and y north at its origin (CloudView::weather_from_world). A host that moves keeps
// the origin fixed and its clouds stay on the ground below them.
glm::dmat3 WeatherFrame(const geo::Observer& observer, double origin_lat_deg,
                        double origin_lon_deg);

// Stars and planets lower than this are not drawn from `height_m` above a sphere of
// `bottom_radius` (m): the planet hides them, below the horizon's dip acos(R / (R + h)) with
// 0.6 deg to spare (refraction lifts them by at most that).
double MinStarElevation(double bottom_radius, double height_m);

// Builds the renderer's view of the sky from an ephemeris computed for `observer`; its stars
// are the ephemeris's stars, then the planets above MinStarElevation. Sun and Moon
// illuminances scale with their distances (solar_illuminance is for 1 au). With `refraction`
// (a table for the observer's height), the stars and planets are drawn at their apparent
// places and the Sun's and Moon's disks at theirs, squeezed (SkyScene::sun_apparent,
// MoonDisk::apparent); their light still comes from their geometric directions (the
// atmosphere's LUTs march straight rays), and the drawn ground's horizon stays the geometric
// one (up to 0.1 deg below the refracted horizon at 10 km). Without it, all are geometric.
SkyState MakeSkyState(const geo::SkyEphemeris& ephemeris, const geo::Observer& observer,
                      const Atmosphere& atmosphere, const geo::Attitude& attitude,
                      double vertical_fov, double aspect,
                      const geo::RefractionTable* refraction = nullptr);

// The direction (unit, ENU) of a body seen through refraction: its elevation the table's
// apparent one, its azimuth kept; unchanged where the table says it is behind the ground.
glm::dvec3 ApparentDirection(const geo::RefractionTable& refraction, const glm::dvec3& direction);

// The sunlight reaching a point of the Moon `axis_distance` m from the Earth's shadow's axis: the
// table's linear interpolation, clamped to its ends (render.frag's MoonLuminance does the same).
glm::dvec3 ShadowSunlight(const MoonDisk::Shadow& shadow, double axis_distance);

// Throws zenith::ArgumentError for a vertical field of view (rad) outside (0, 180) deg (field
// "fov_deg", the message in degrees) or an aspect (width / height) that is not positive and
// finite (field "aspect"). What every front end checks a projection with.
void ValidateProjection(double vertical_fov, double aspect);

// When, where and how one frame is seen.
struct FrameSetup {
    geo::Time time;
    geo::Observer observer{0.0, 0.0, 0.0};
    geo::Attitude attitude;  // of the camera: aerospace 3-2-1 Euler angles from local NED
    // The camera's columns right, up, backward in the observer's ENU frame, instead of attitude.
    std::optional<glm::dmat3> enu_from_view;
    double vertical_fov = 1.0471975511965976;  // rad (60 deg)
    double aspect = 16.0 / 9.0;                // the viewport's width / height
    // The air the bodies are seen through (geo/refraction.h; a METAR's QNH and temperature, or
    // ISA's): Earth's. None: every body at its geometric place (another planet's sky).
    std::optional<geo::RefractionAir> refraction = geo::RefractionAir{};

    void Validate() const {
        ValidateProjection(vertical_fov, aspect);
        if (refraction) refraction->Validate();
    }
};

struct SkyFrame : SkyState {
    geo::SkyEphemeris ephemeris;  // at setup.time for setup.observer, stars above the dip
};

// The refraction table of the last frames, traced again (0.8 ms) only when the air or the
// planet changes or the observer's height moves by more than keeps the horizon's dip, the
// quantity that changes fastest with height, within 5" (0.5 m at 100 m, 9 m at 10 km).
class RefractionCache {
  public:
    const geo::RefractionTable& Get(const geo::RefractionAir& air, double height_m,
                                    double planet_radius_m);
    void Clear() { table_.reset(); }  // the next Get makes its table for its own height

  private:
    std::optional<geo::RefractionTable> table_;
};

// The one frame builder: the ephemeris (from `calculator`, which holds the star catalogue and
// caches their places), then MakeSkyState with setup.refraction's table (from `cache` when
// given, which a frame loop keeps). Validates the setup first.
SkyFrame BuildSkyFrame(const geo::Ephemeris& calculator, const FrameSetup& setup,
                       const Atmosphere& atmosphere, RefractionCache* cache = nullptr);

}  // namespace zenith::sky
