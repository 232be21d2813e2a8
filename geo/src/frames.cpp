#include "zenith/geo/frames.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "zenith/base/units.h"

namespace zenith::geo {

Attitude Attitude::FromDegrees(double heading_deg, double pitch_deg, double roll_deg) {
    return {Radians(heading_deg), Radians(pitch_deg), Radians(roll_deg)};
}

glm::dmat3 NedFromBody(const Attitude& a) {
    const double cy = std::cos(a.heading_rad), sy = std::sin(a.heading_rad);
    const double cp = std::cos(a.pitch_rad), sp = std::sin(a.pitch_rad);
    const double cr = std::cos(a.roll_rad), sr = std::sin(a.roll_rad);
    // glm is column-major: each glm::dvec3 below is one column (a body axis in NED).
    return glm::dmat3(glm::dvec3(cp * cy, cp * sy, -sp),
                      glm::dvec3(sr * sp * cy - cr * sy, sr * sp * sy + cr * cy, sr * cp),
                      glm::dvec3(cr * sp * cy + sr * sy, cr * sp * sy - sr * cy, cr * cp));
}

glm::dmat3 EcefFromNed(double lat_deg, double lon_deg) {
    const double sphi = std::sin(Radians(lat_deg)), cphi = std::cos(Radians(lat_deg));
    const double slam = std::sin(Radians(lon_deg)), clam = std::cos(Radians(lon_deg));
    return glm::dmat3(glm::dvec3(-sphi * clam, -sphi * slam, cphi), glm::dvec3(-slam, clam, 0.0),
                      glm::dvec3(-cphi * clam, -cphi * slam, -sphi));
}

glm::dmat3 EcefFromEnu(double lat_deg, double lon_deg) {
    return EcefFromNed(lat_deg, lon_deg) * EnuFromNed();
}

glm::dmat3 EnuFromNed() {
    return glm::dmat3(glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(1.0, 0.0, 0.0),
                      glm::dvec3(0.0, 0.0, -1.0));
}

glm::dquat EcefFromBody(const Attitude& attitude, double lat_deg, double lon_deg) {
    return glm::normalize(glm::quat_cast(EcefFromNed(lat_deg, lon_deg) * NedFromBody(attitude)));
}

Attitude AttitudeFromEcefFromBody(const glm::dquat& ecef_from_body, double lat_deg,
                                  double lon_deg) {
    const glm::dmat3 m =
        glm::transpose(EcefFromNed(lat_deg, lon_deg)) * glm::mat3_cast(ecef_from_body);
    // m[col][row]: C31 = -sin(pitch), C21/C11 = tan(heading), C32/C33 = tan(roll).
    Attitude a;
    a.pitch_rad = std::asin(std::clamp(-m[0][2], -1.0, 1.0));
    a.heading_rad = std::atan2(m[0][1], m[0][0]);
    if (a.heading_rad < 0.0) a.heading_rad += 2.0 * std::numbers::pi;
    a.roll_rad = std::atan2(m[1][2], m[2][2]);
    return a;
}

glm::dmat3 BodyFromView() {
    return glm::dmat3(glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, -1.0),
                      glm::dvec3(-1.0, 0.0, 0.0));
}

glm::dmat3 EnuFromView(const Attitude& attitude) {
    // EnuFromNed() * NedFromBody(attitude) * BodyFromView() written out, so that the columns are
    // exact for a level camera: forward from heading and pitch, right level at zero roll, then
    // both turned about forward by the roll (right wing down for positive roll).
    const double ch = std::cos(attitude.heading_rad), sh = std::sin(attitude.heading_rad);
    const double cp = std::cos(attitude.pitch_rad), sp = std::sin(attitude.pitch_rad);
    const glm::dvec3 forward{sh * cp, ch * cp, sp};
    const glm::dvec3 level_right{ch, -sh, 0.0};
    const glm::dvec3 level_up = glm::cross(level_right, forward);
    const double cr = std::cos(attitude.roll_rad), sr = std::sin(attitude.roll_rad);
    const glm::dvec3 right = level_right * cr - level_up * sr;
    const glm::dvec3 up = level_up * cr + level_right * sr;
    return glm::dmat3(right, up, -forward);
}

}  // namespace zenith::geo
