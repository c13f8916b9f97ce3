#pragma once
// A raster that is a series in time: a netCDF variable over (time, y, x), which GDAL presents
// as one band per time. Each band is read as io::read_raster reads one (the scene's CRS, the
// memory limit, nodata as NaN), and the time axis is read from the file's CF attributes.

#include <string>
#include <vector>

#include "swemps/io/cf_time.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::io {

struct RasterSeries {
  std::string time_name;      // the time axis's variable ("time")
  std::vector<double> times;  // per band, in the axis's own units
  CfTimeUnits time_units;     // how many seconds a unit is, and since when
  std::string value_units;    // the variable's "units" attribute; empty when it has none
  std::vector<terrain::GriddedField> frames;  // per band, in order of the file
};

// Reads every band of request.path (request.band is ignored). Throws std::runtime_error, one
// line naming the purpose and the file, when the file cannot be read as a raster, has no time
// axis or more than one axis besides y and x, when the axis's units are not CF time units, or
// when the memory limit would be passed (counted over all bands).
RasterSeries read_raster_series(const RasterRequest& request);

}  // namespace swemps::io
