// What the netCDF writer's files share: error checks, stored values, and the grid's CRS as
// CF grid-mapping attributes.

#include <cpl_conv.h>
#include <cpl_error.h>
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "netcdf_layout.hpp"
#include "swemps/io/gdal_messages.hpp"

namespace swemps::io::netcdf {

std::string quoted(const std::filesystem::path& p) {
  // Appended piecewise: `"'" + string` trips a false -Wrestrict warning in GCC 12.
  std::string text(1, '\'');
  text += p.string();
  text += '\'';
  return text;
}

void check(int status, const std::string& purpose, const std::filesystem::path& file) {
  if (status != NC_NOERR) {
    throw std::runtime_error("netCDF: cannot " + purpose + " (file " + quoted(file) +
                             "): " + nc_strerror(status));
  }
}

int create_netcdf4(const std::filesystem::path& file) {
  int ncid = -1;
  const int status = nc_create(file.c_str(), NC_NETCDF4 | NC_CLOBBER, &ncid);
  if (status == NC_NOERR) return ncid;
  std::string message =
      std::string("netCDF: cannot create the file ") + quoted(file) + ": " + nc_strerror(status);
  // A missing folder is reported as a permission problem; say what is really wrong.
  const std::filesystem::path folder = file.parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec)) {
    message += " (" + quoted(folder) + " is not an existing folder)";
  }
  throw std::runtime_error(message);
}

std::vector<float> to_stored_floats(std::span<const double> values) {
  std::vector<float> out(values.size());
  std::transform(values.begin(), values.end(), out.begin(),
                 [](double v) { return std::isnan(v) ? kFillFloat : static_cast<float>(v); });
  return out;
}

double to_stored(double v) { return std::isnan(v) ? kFillDouble : v; }

std::string exact_text(double v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), end);
}

// ---------------------------------------------------------------------------------------
// Coordinate reference system

namespace {

// GDAL 3.6 has no export of a CRS to CF attributes (that came with 3.9), so the common
// projections of flood studies are translated here from their WKT1 parameters, which GDAL
// normalises to degrees and metres. Readers that rely on the CF attributes alone (Panoply)
// then place the grid; any other projection keeps only the WKT, which GDAL, QGIS and
// xarray-based tools read.
std::vector<CfParameter> cf_projection_parameters(const OGRSpatialReference& srs,
                                                  std::string& grid_mapping_name) {
  const char* projection = srs.GetAttrValue("PROJECTION");
  const std::string p = projection ? projection : "";
  const auto param = [&](const char* cf_name, const char* gdal_name) {
    return CfParameter{cf_name, {srs.GetNormProjParm(gdal_name, 0.0)}};
  };
  const auto parallels = [&] {
    return CfParameter{"standard_parallel",
                       {srs.GetNormProjParm(SRS_PP_STANDARD_PARALLEL_1, 0.0),
                        srs.GetNormProjParm(SRS_PP_STANDARD_PARALLEL_2, 0.0)}};
  };
  const CfParameter false_easting = param("false_easting", SRS_PP_FALSE_EASTING);
  const CfParameter false_northing = param("false_northing", SRS_PP_FALSE_NORTHING);

  if (p == SRS_PT_TRANSVERSE_MERCATOR) {  // UTM and most national grids
    grid_mapping_name = "transverse_mercator";
    return {param("scale_factor_at_central_meridian", SRS_PP_SCALE_FACTOR),
            param("longitude_of_central_meridian", SRS_PP_CENTRAL_MERIDIAN),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_ORIGIN), false_easting,
            false_northing};
  }
  if (p == SRS_PT_LAMBERT_CONFORMAL_CONIC_2SP) {
    grid_mapping_name = "lambert_conformal_conic";
    return {parallels(), param("longitude_of_central_meridian", SRS_PP_CENTRAL_MERIDIAN),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_ORIGIN), false_easting,
            false_northing};
  }
  if (p == SRS_PT_ALBERS_CONIC_EQUAL_AREA) {
    grid_mapping_name = "albers_conical_equal_area";
    return {parallels(), param("longitude_of_central_meridian", SRS_PP_LONGITUDE_OF_CENTER),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_CENTER), false_easting,
            false_northing};
  }
  if (p == SRS_PT_LAMBERT_AZIMUTHAL_EQUAL_AREA) {
    grid_mapping_name = "lambert_azimuthal_equal_area";
    return {param("longitude_of_projection_origin", SRS_PP_LONGITUDE_OF_CENTER),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_CENTER), false_easting,
            false_northing};
  }
  if (p == SRS_PT_MERCATOR_1SP) {
    grid_mapping_name = "mercator";
    return {param("longitude_of_projection_origin", SRS_PP_CENTRAL_MERIDIAN),
            param("scale_factor_at_projection_origin", SRS_PP_SCALE_FACTOR), false_easting,
            false_northing};
  }
  grid_mapping_name.clear();
  return {};
}

}  // namespace

Crs describe_crs(const std::string& wkt, const std::filesystem::path& file) {
  const std::string where = "NetcdfWriter: CRS of the grid for " + quoted(file);
  OGRSpatialReference srs;
  {
    // GDAL's complaint goes into the exception instead of onto stderr.
    const QuietGdalErrors quiet;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) {
      throw std::invalid_argument(where +
                                  " is not WKT that GDAL can read: " + CPLGetLastErrorMsg());
    }
  }
  if (!srs.IsProjected()) {
    throw std::invalid_argument(where + " is not a projected CRS (x and y must be metres)");
  }
  const char* unit_name = nullptr;
  const double unit_m = srs.GetLinearUnits(&unit_name);
  if (std::abs(unit_m - 1.0) > 1e-12) {
    throw std::invalid_argument(where + " has unit '" + (unit_name ? unit_name : "?") +
                                "', not metres");
  }

  Crs crs;
  // WKT1 is what older GDAL and QGIS versions read from spatial_ref; a CRS that WKT1
  // cannot express is written as WKT2 instead.
  char* text = nullptr;
  OGRErr status = srs.exportToWkt(&text);
  if (status != OGRERR_NONE) {
    CPLFree(text);
    text = nullptr;
    const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
    status = srs.exportToWkt(&text, options);
  }
  if (status != OGRERR_NONE || text == nullptr) {
    CPLFree(text);
    throw std::invalid_argument(where + " cannot be written as WKT");
  }
  crs.wkt = text;
  CPLFree(text);
  crs.name = srs.GetName() ? srs.GetName() : "";
  crs.params = cf_projection_parameters(srs, crs.grid_mapping_name);
  if (!crs.grid_mapping_name.empty()) {
    OGRErr err = OGRERR_NONE;
    const double semi_major = srs.GetSemiMajor(&err);
    const double inverse_flattening = srs.GetInvFlattening(&err);
    crs.params.push_back({"semi_major_axis", {semi_major}});
    crs.params.push_back({"inverse_flattening", {inverse_flattening}});
    crs.params.push_back({"longitude_of_prime_meridian", {srs.GetPrimeMeridian()}});
  }
  return crs;
}
std::string geo_transform(const Grid& g) {
  const double x_left = g.x0 - 0.5 * g.dx;
  const double y_top = g.y0 + (static_cast<double>(g.ny) - 0.5) * g.dy;
  return exact_text(x_left) + " " + exact_text(g.dx) + " 0 " + exact_text(y_top) + " 0 " +
         exact_text(-g.dy);
}

}  // namespace swemps::io::netcdf
