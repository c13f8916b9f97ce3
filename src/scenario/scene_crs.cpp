#include "scene_crs.hpp"

#include <stdexcept>
#include <utility>

#include "swemps/scenario/memory_check.hpp"

namespace swemps::scenario {

io::RasterRequest SceneCrs::request(const RasterSpec& spec, const std::string& purpose,
                                    const std::string& setting) const {
  io::RasterRequest r;
  r.path = spec.path;
  r.purpose = purpose;
  r.memory_limit_bytes = usable_memory_bytes();
  if (!spec.crs.empty()) {
    r.target_crs = spec.crs;
    r.crs_setting = setting;
  } else {
    r.target_crs = target_;
    r.crs_setting = target_setting_.empty() ? setting : target_setting_;
  }
  return r;
}

terrain::GriddedField SceneCrs::read(const RasterSpec& spec, const std::string& purpose,
                                     const std::string& setting, const std::string& json_path,
                                     io::RasterRequest::Resampling resampling) {
  return read_surface(spec, purpose, setting, json_path, 1, resampling).field;
}

io::RasterSurface SceneCrs::read_surface(const RasterSpec& spec, const std::string& purpose,
                                         const std::string& setting, const std::string& json_path,
                                         std::size_t refinement,
                                         io::RasterRequest::Resampling resampling) {
  io::RasterRequest r = request(spec, purpose, setting);
  r.resampling = resampling;
  io::RasterSurface surface = [&] {
    try {
      return io::read_raster_surface(r, refinement);
    } catch (const std::runtime_error& e) {
      reader_failed(json_path, e.what());
    }
  }();
  agree(surface.field, spec, purpose, setting, json_path);
  return surface;
}

io::RasterSeries SceneCrs::read_series(const RasterSpec& spec, const std::string& purpose,
                                       const std::string& setting, const std::string& json_path) {
  io::RasterSeries series;
  try {
    series = io::read_raster_series(request(spec, purpose, setting));
  } catch (const std::runtime_error& e) {
    reader_failed(json_path, e.what());
  }
  agree(series.frames.front(), spec, purpose, setting, json_path);
  return series;
}

void SceneCrs::agree(const terrain::GriddedField& field, const RasterSpec& spec,
                     const std::string& purpose, const std::string& setting,
                     const std::string& json_path) {
  if (known_ && field.crs_wkt().empty() != wkt_.empty()) {
    throw ScenarioError(json_path,
                        purpose + " '" + spec.path.string() +
                            (wkt_.empty() ? "' with a CRS in a scene whose rasters have none"
                                          : "' without a CRS in a scene that has one"),
                        "every raster with a CRS, or none with one");
  }
  if (!known_) {
    known_ = true;
    wkt_ = field.crs_wkt();
    // Later rasters follow the CRS as given (shorter in messages), else the file's own.
    target_ = spec.crs.empty() ? wkt_ : spec.crs;
    target_setting_ = spec.crs.empty() ? "the CRS of " + json_path : setting;
  }
}

void SceneCrs::reader_failed(const std::string& json_path, const std::string& what) {
  throw ScenarioError(json_path, what,
                      "a raster GDAL can read, in a projected CRS in metres (or with a "
                      "\"crs\" to warp it to)");
}

}  // namespace swemps::scenario
