// Frames and attitudes: the body, local NED/ENU, ECEF and camera-view axes, and the one Attitude
// type every layer uses. Rotations are named target_from_source and map column vectors:
// v_target = target_from_source * v_source.
//
//   body  x forward (nose), y right wing, z down           (aerospace convention)
//   NED   x north, y east, z down, at a geodetic position   (WGS84 ellipsoid normal)
//   ENU   x east, y north, z up, at the same position       (what geo/ reports directions in)
//   view  x right, y up, z backward (OpenGL eye space): the camera looks along -z
//   ECEF  WGS84 Earth-centred, Earth-fixed
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace zenith::geo {

// The body axes relative to the local NED frame as aerospace 3-2-1 Euler angles: turn by
// heading about down, then by pitch about the new right wing, then by roll about the nose.
// Heading from true north clockwise, pitch nose up positive, roll right wing down positive.
struct Attitude {
    double heading_rad = 0.0;
    double pitch_rad = 0.0;
    double roll_rad = 0.0;

    static Attitude FromDegrees(double heading_deg, double pitch_deg, double roll_deg);
};

glm::dmat3 NedFromBody(const Attitude& attitude);
// Columns north, east, down (or east, north, up) of the local frame at (lat, lon) in ECEF.
glm::dmat3 EcefFromNed(double lat_deg, double lon_deg);
glm::dmat3 EcefFromEnu(double lat_deg, double lon_deg);
// The constant swap between the two local frames (its own inverse).
glm::dmat3 EnuFromNed();

glm::dquat EcefFromBody(const Attitude& attitude, double lat_deg, double lon_deg);
// Its inverse; at pitch +-90 deg heading and roll share one angle and heading takes it all.
Attitude AttitudeFromEcefFromBody(const glm::dquat& ecef_from_body, double lat_deg, double lon_deg);

// A camera looking along the body's nose, its up the body's -z: view x = body y (right),
// view y = -body z (up), view z = -body x (backward).
glm::dmat3 BodyFromView();
// Columns right, up, backward of that camera in the local ENU frame.
glm::dmat3 EnuFromView(const Attitude& attitude);

}  // namespace zenith::geo
