#include "vector_files.hpp"

#include <stdexcept>
#include <system_error>

namespace swemps::io::vector {

NewLayer create_layer(const std::filesystem::path& file, VectorFile format, const char* name,
                      const std::string& wkt, OGRwkbGeometryType type) {
  GDALDriver* driver =
      GetGDALDriverManager()->GetDriverByName(format == VectorFile::gpkg ? "GPKG" : "GeoJSON");
  if (!driver) throw std::runtime_error("GDAL has no driver for it");
  OGRSpatialReference crs;
  crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (wkt.empty()) {
    crs.SetLocalCS("local coordinates in metres");
    crs.SetLinearUnits(SRS_UL_METER, 1.0);
  } else if (crs.importFromWkt(wkt.c_str()) != OGRERR_NONE) {
    throw std::runtime_error("its CRS is not WKT");
  }
  NewLayer out;
  out.file.reset(driver->Create(file.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!out.file) throw std::runtime_error("cannot create it");
  out.layer = out.file->CreateLayer(name, &crs, type, nullptr);
  if (!out.layer) throw std::runtime_error("cannot create its layer");
  return out;
}

std::filesystem::path partial_name(const std::filesystem::path& file) {
  std::filesystem::path partial = file;
  partial.replace_filename(file.stem().string() + ".partial" + file.extension().string());
  return partial;
}

void write_then_rename(const std::filesystem::path& file,
                       const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path partial = partial_name(file);
  std::error_code ec;
  std::filesystem::remove(partial, ec);
  try {
    write(partial);
  } catch (...) {
    std::filesystem::remove(partial, ec);
    throw;
  }
  std::filesystem::rename(partial, file, ec);
  if (ec) {
    std::filesystem::remove(partial, ec);
    throw std::runtime_error("cannot rename '" + partial.string() + "' to '" + file.string() + "'");
  }
}

}  // namespace swemps::io::vector
