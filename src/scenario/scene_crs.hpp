#pragma once
// The scene's CRS as its rasters are read one after another (build.cpp, rain_maps.cpp):
// the first raster with a raster bed or a "crs" key settles it, and every later raster is
// warped to it. Internal to the scenario module.

#include <cstddef>
#include <string>

#include "swemps/io/raster_reader.hpp"
#include "swemps/io/raster_series.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

class SceneCrs {
 public:
  // The request for a raster: to its own "crs" when it has one (`setting` names that key in
  // messages), otherwise to the scene's CRS once known.
  io::RasterRequest request(const RasterSpec& spec, const std::string& purpose,
                            const std::string& setting) const;

  // Reads the raster; reader errors become scenario errors at `json_path`. A raster without
  // a CRS in a scene that has one (or the reverse) could lie anywhere relative to the others.
  terrain::GriddedField read(
      const RasterSpec& spec, const std::string& purpose, const std::string& setting,
      const std::string& json_path,
      io::RasterRequest::Resampling resampling = io::RasterRequest::Resampling::bilinear);

  // The same, as a surface refined `refinement` times where it is warped
  // (io::read_raster_surface).
  io::RasterSurface read_surface(
      const RasterSpec& spec, const std::string& purpose, const std::string& setting,
      const std::string& json_path, std::size_t refinement,
      io::RasterRequest::Resampling resampling = io::RasterRequest::Resampling::bilinear);

  // The same for a series of maps in time (io::read_raster_series); every map is warped
  // alike.
  io::RasterSeries read_series(const RasterSpec& spec, const std::string& purpose,
                               const std::string& setting, const std::string& json_path);

  const std::string& wkt() const { return wkt_; }

 private:
  // Settles the scene's CRS on the first raster read, and refuses one whose CRS (or lack of
  // one) does not match the rasters before it.
  void agree(const terrain::GriddedField& field, const RasterSpec& spec, const std::string& purpose,
             const std::string& setting, const std::string& json_path);
  [[noreturn]] static void reader_failed(const std::string& json_path, const std::string& what);

  bool known_ = false;
  std::string wkt_, target_, target_setting_;
};

}  // namespace swemps::scenario
