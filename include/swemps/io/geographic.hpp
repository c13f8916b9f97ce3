#pragma once
// A point given by longitude and latitude (WGS 84), placed in a scene's projected CRS, and
// the way true north points there: what a fault plane from an earthquake catalogue needs to
// lie on the map (its strike is measured from true north, the map's +y from grid north).

#include <string>

namespace swemps::io {

struct ProjectedPoint {
  double x_m = 0.0, y_m = 0.0;
  // True north's bearing clockwise from the map's +y, degrees (the grid convergence).
  double north_bearing_deg = 0.0;
};

// Throws std::runtime_error when `crs_wkt` is empty (a scene without a CRS) or GDAL cannot
// transform the point.
ProjectedPoint project_geographic(double longitude_deg, double latitude_deg,
                                  const std::string& crs_wkt);

}  // namespace swemps::io
