#include "swemps/io/geographic.hpp"

#include <ogr_spatialref.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace swemps::io {

namespace {

// A thousandth of a degree of latitude (about 110 m) north: far enough that the projected
// step is not round-off, near enough that the map's distortion over it is not felt.
constexpr double kNorthStepDeg = 1e-3;

}  // namespace

ProjectedPoint project_geographic(double longitude_deg, double latitude_deg,
                                  const std::string& crs_wkt) {
  if (crs_wkt.empty()) {
    throw std::runtime_error("a position in longitude and latitude in a scene without a CRS");
  }
  OGRSpatialReference geographic, target;
  geographic.importFromEPSG(4326);
  geographic.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (target.importFromWkt(crs_wkt.c_str()) != OGRERR_NONE) {
    throw std::runtime_error("the scene's CRS is not one GDAL reads");
  }
  target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const auto destroy = [](OGRCoordinateTransformation* t) {
    OGRCoordinateTransformation::DestroyCT(t);
  };
  const std::unique_ptr<OGRCoordinateTransformation, decltype(destroy)> transform(
      OGRCreateCoordinateTransformation(&geographic, &target), destroy);
  if (!transform) throw std::runtime_error("no transformation from longitude/latitude to the CRS");
  double x[2] = {longitude_deg, longitude_deg};
  double y[2] = {latitude_deg, latitude_deg + kNorthStepDeg};
  if (!transform->Transform(2, x, y) || !std::isfinite(x[0]) || !std::isfinite(y[1])) {
    throw std::runtime_error("longitude " + std::to_string(longitude_deg) + ", latitude " +
                             std::to_string(latitude_deg) + " lies outside the CRS's reach");
  }
  ProjectedPoint out;
  out.x_m = x[0];
  out.y_m = y[0];
  out.north_bearing_deg = std::atan2(x[1] - x[0], y[1] - y[0]) * 180.0 / std::numbers::pi;
  return out;
}

}  // namespace swemps::io
