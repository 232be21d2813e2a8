// Prints the Sun's elevation at J2000.0 over Greenwich: proves the installed headers and
// library work from a separate project.
#include <cmath>
#include <cstdio>

#include <zenith/geo/ephemeris.h>

int main() {
    const zenith::geo::Time t = zenith::geo::TimeFromIso8601("2000-01-01T12:00:00Z");
    const zenith::geo::Observer greenwich(51.4769, 0.0, 46.0);
    const auto e = zenith::geo::Ephemeris().Compute(t, greenwich);
    const double elevation_deg = e.sun.elevation * 180.0 / 3.14159265358979323846;
    std::printf("sun elevation %.3f deg\n", elevation_deg);
    return std::abs(elevation_deg - 15.5) < 1.0 ? 0 : 1;  // winter noon sun at 51.5 N
}
