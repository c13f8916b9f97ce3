#pragma once
// Private to the io module: what the vector files it writes share (the inundation line, the
// pathlines): the layer's CRS, and the file written under a temporary name the drivers still
// know by its extension, then renamed, so that a file with its final name is whole.

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <functional>
#include <string>

#include "swemps/io/tsunami_products.hpp"

namespace swemps::io::vector {

// A new file of `format` holding one empty layer `name` of geometry `type`, in the CRS `wkt`
// (axes in GIS order); without one (empty), local metres: an engineering CRS, which a GIS does
// not take for degrees (as it takes a GeoPackage layer without any). Throws
// std::runtime_error saying what failed ("cannot create it"), for the caller to name the file.
struct NewLayer {
  GDALDatasetUniquePtr file;
  OGRLayer* layer = nullptr;
};
NewLayer create_layer(const std::filesystem::path& file, VectorFile format, const char* name,
                      const std::string& wkt, OGRwkbGeometryType type);

// "<stem>.partial<ext>" beside `file`.
std::filesystem::path partial_name(const std::filesystem::path& file);

// Calls write(partial) and renames the partial file to `file`; on failure removes it and
// rethrows (a failed rename as std::runtime_error naming both files).
void write_then_rename(const std::filesystem::path& file,
                       const std::function<void(const std::filesystem::path&)>& write);

}  // namespace swemps::io::vector
