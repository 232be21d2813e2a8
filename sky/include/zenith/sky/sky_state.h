// From where things are (geo) to what the renderer draws: camera, lights, Moon disk and stars in
// the atmosphere's planet-centred frame.
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
#include <vector>

#include "zenith/geo/ephemeris.h"
#include "zenith/geo/frames.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

struct SkyState {
    Camera camera;
    Lights lights;
    MoonDisk moon;
    std::vector<StarPoint> stars;
    double sun_elevation = 0.0;  // rad, geometric, for exposure and day/night decisions
};

// Lambertian sphere of `albedo` at phase angle `phase_angle` (rad): the illuminance it sends to
// the observer per unit solar illuminance, times the solid angle it subtends (Moon as a light).
double LambertSphereIlluminanceFactor(double albedo, double phase_angle, double angular_radius);

// The rotation from the renderer's frame at `observer` (its ENU axes) to the weather frame of
// a weather map whose origin is at (origin_lat_deg, origin_lon_deg): ENU axes there, so the map's
// x runs east and y north at its origin (CloudView::weather_from_world). A host that moves keeps
// the origin fixed and its clouds stay on the ground below them.
glm::dmat3 WeatherFrame(const geo::Observer& observer, double origin_lat_deg,
                        double origin_lon_deg);

// Stars and planets lower than this are not drawn (the planet hides them; refraction lifts them
// by at most 0.6 deg).
inline constexpr double kMinStarElevation = -0.1;  // rad

// Builds the renderer's view of the sky from an ephemeris computed for `observer`; its stars
// are the ephemeris's stars, then the planets above kMinStarElevation. Sun and Moon
// illuminances scale with their distances (solar_illuminance is for 1 au).
SkyState MakeSkyState(const geo::SkyEphemeris& ephemeris, const geo::Observer& observer,
                      const Atmosphere& atmosphere, const geo::Attitude& attitude,
                      double vertical_fov, double aspect);

}  // namespace zenith::sky
