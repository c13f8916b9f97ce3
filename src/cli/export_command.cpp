// `swe-mps export`: a finished result's GeoTIFF maps and gauge CSV, beside it, and a tsunami
// run's inundation line and gauge arrivals.

#include "swemps/cli/export_command.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "swemps/cli/output.hpp"
#include "swemps/cli/run_command.hpp"
#include "swemps/io/flood_products.hpp"
#include "swemps/io/tsunami_products.hpp"

namespace swemps::cli {

void export_products(const Options& options) {
  const std::filesystem::path& result = options.scenario;
  std::filesystem::path prefix = options.output.value_or(result);
  if (!options.output) prefix.replace_extension();
  const io::TiffLayout layout =
      options.format == "geotiff" ? io::TiffLayout::plain : io::TiffLayout::cloud_optimised;
  std::vector<std::filesystem::path> maps;
  // "all" is every map, as no list is.
  const bool all = options.maps.size() == 1 && options.maps.front() == "all";
  try {
    maps = io::export_maps(result, all ? std::vector<std::string>{} : options.maps, layout, prefix);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  }
  for (const auto& m : maps) spdlog::info("wrote {}", m.string());
  std::filesystem::path csv = prefix;
  csv += "_gauges.csv";
  try {
    if (io::export_gauges(result, csv)) spdlog::info("wrote {}", csv.string());
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  }
  // A tsunami run's line (as a GeoPackage) and gauge arrivals, as the run's end makes them.
  bool tsunami = false;
  try {
    tsunami = io::has_tsunami_maps(result);
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  }
  if (tsunami) write_tsunami_products(result, prefix, io::VectorFile::gpkg);
}

}  // namespace swemps::cli
