// Geoid undulation N (the geoid's height above the WGS84 ellipsoid, metres), from a grid in
// NOAA's GTX format, so heights above mean sea level become ellipsoidal heights: h = H + N.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::geo {

// A geoid grid that cannot be read or is not a GTX grid; the message names the file.
class GeoidError : public InputError {
  public:
    using InputError::InputError;
};

// GTX: big-endian header (lower-left lat, lon, spacing lat, lon in degrees; rows, columns), then
// rows x columns big-endian float32 from south-west, row by row. Bilinear interpolation; on the
// 15' EGM96 grid that is within a few centimetres of the grid's own model except in steep
// mountains (decimetres).
class GeoidGrid {
  public:
    // Throws GeoidError naming the file and what is wrong with it. Reads at most the size the
    // header announces (a 1' world grid is 933 MB; larger files are refused).
    static GeoidGrid LoadGtx(const std::filesystem::path& path);
    // $ZENITH_GEOID_GTX if set, else /usr/share/proj/egm96_15.gtx (Debian's proj-data); loaded
    // once; nullptr when neither can be read.
    static const GeoidGrid* Default();

    double UndulationAt(double lat_deg, double lon_deg) const;
    const std::string& source() const { return source_; }

  private:
    std::string source_;
    double lat0_deg_ = 0.0, lon0_deg_ = 0.0, dlat_deg_ = 0.0, dlon_deg_ = 0.0;
    int rows_ = 0, cols_ = 0;
    bool wraps_ = false;  // columns span 360 degrees
    std::vector<float> values_;
};

}  // namespace zenith::geo
