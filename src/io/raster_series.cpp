#include "swemps/io/raster_series.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "swemps/io/gdal_messages.hpp"

namespace swemps::io {

namespace {

// "{time}" -> "time"; several names ("{time,level}") or none: empty.
std::string single_extra_dimension(const char* text) {
  if (text == nullptr) return {};
  std::string s = text;
  if (s.size() < 3 || s.front() != '{' || s.back() != '}') return {};
  s = s.substr(1, s.size() - 2);
  return s.find(',') == std::string::npos ? s : std::string{};
}

}  // namespace

RasterSeries read_raster_series(const RasterRequest& request) {
  const std::string prefix = request.purpose + " '" + request.path.string() + "': ";
  const auto fail = [&](const std::string& problem) { throw std::runtime_error(prefix + problem); };
  // The first band, read as any raster, brings the reader's own errors (not found, no CRS,
  // too large) before the series is looked at.
  RasterRequest band = request;
  band.band = 1;
  RasterSeries series;
  series.frames.push_back(read_raster(band));

  register_gdal_drivers();
  const QuietGdalErrors quiet;
  GDALDatasetUniquePtr dataset(
      GDALDataset::Open(request.path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset) fail("cannot be opened again" + gdal_detail());
  const char* extra_text = dataset->GetMetadataItem("NETCDF_DIM_EXTRA");
  const std::string extra = extra_text == nullptr ? "" : extra_text;
  series.time_name = single_extra_dimension(extra_text);
  if (series.time_name.empty()) {
    fail(extra.empty()
             ? "has no time axis: a series of maps is a netCDF variable over "
               "(time, y, x); a single map is a raster"
             : "has the axes " + extra + " besides y and x; a series of maps has one, its time");
  }
  const char* units = dataset->GetMetadataItem((series.time_name + "#units").c_str());
  if (units == nullptr) fail("its time axis '" + series.time_name + "' has no units");
  const auto parsed = parse_cf_time_units(units);
  if (!parsed) {
    fail("its time axis '" + series.time_name + "' has the units '" + units +
         "', not CF time units such as \"minutes since 2024-06-01 00:00:00\"");
  }
  series.time_units = *parsed;
  const int bands = dataset->GetRasterCount();
  const std::string time_key = "NETCDF_DIM_" + series.time_name;
  for (int b = 1; b <= bands; ++b) {
    GDALRasterBand* raster_band = dataset->GetRasterBand(b);
    const char* value = raster_band->GetMetadataItem(time_key.c_str());
    char* end = nullptr;
    const double t = value == nullptr ? 0.0 : std::strtod(value, &end);
    if (value == nullptr || end == value) {
      fail("band " + std::to_string(b) + " has no " + series.time_name + " value");
    }
    series.times.push_back(t);
  }
  series.value_units = dataset->GetRasterBand(1)->GetUnitType();
  dataset.reset();

  const double cells = static_cast<double>(series.frames.front().values().size());
  if (request.memory_limit_bytes > 0 &&
      cells * bands * kRasterBytesPerCell > static_cast<double>(request.memory_limit_bytes)) {
    fail(std::to_string(bands) + " maps of " +
         std::to_string(series.frames.front().values().size()) +
         " cells would need more memory than this machine has");
  }
  for (int b = 2; b <= bands; ++b) {
    band.band = b;
    series.frames.push_back(read_raster(band));
  }
  return series;
}

}  // namespace swemps::io
