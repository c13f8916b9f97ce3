#pragma once
// `swe-mps export RESULT.nc`: the GeoTIFF maps and the gauge CSV of a run's netCDF result,
// written beside it (io/flood_products.hpp), as a run writes them at its end when its scene
// asks.

#include <string>

#include "swemps/cli/options.hpp"

namespace swemps::cli {

// Throws UsageError for an unknown map name, OutputError when a file cannot be read or
// written.
void export_products(const Options& options);

}  // namespace swemps::cli
