#include "swemps/io/pathline_writer.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "swemps/io/gdal_messages.hpp"
#include "vector_files.hpp"

namespace swemps::io {

namespace {

const char* fate_name(maps::Pathline::Fate fate) {
  switch (fate) {
    case maps::Pathline::Fate::left: return "left the domain";
    case maps::Pathline::Fate::merged: return "merged";
    case maps::Pathline::Fate::in_domain: break;
  }
  return "in the domain";
}

double length_m(const maps::Pathline& line) {
  double length = 0.0;
  for (std::size_t k = 1; k < line.x.size(); ++k) {
    length += std::hypot(line.x[k] - line.x[k - 1], line.y[k] - line.y[k - 1]);
  }
  return length;
}

void write_layer(const std::vector<maps::Pathline>& lines, const PathlineLayer& about,
                 const std::filesystem::path& file, VectorFile format) {
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("cannot write the pathlines '" + file.string() + "': " + what +
                             gdal_detail());
  };
  const bool gpkg = format == VectorFile::gpkg;
  vector::NewLayer created;
  try {
    created = vector::create_layer(file, format, "pathlines", about.crs_wkt,
                                   gpkg ? wkbLineStringM : wkbLineString);
  } catch (const std::runtime_error& e) {
    fail(e.what());
  }
  GDALDataset* out = created.file.get();
  OGRLayer* layer = created.layer;
  const bool sources = !about.source_names.empty();
  struct Field {
    const char* name;
    OGRFieldType type;
  };
  std::vector<Field> fields{
      {"pathline", OFTInteger}, {"source", OFTString},    {"start_time_s", OFTReal},
      {"end_time_s", OFTReal},  {"fate", OFTString},      {"merged_into", OFTInteger},
      {"length_m", OFTReal},    {"vertices", OFTInteger}, {"time_units", OFTString}};
  if (!sources) fields.erase(fields.begin() + 1);
  if (!gpkg) fields.push_back({"time_s", OFTRealList});
  for (const Field& f : fields) {
    OGRFieldDefn field(f.name, f.type);
    if (layer->CreateField(&field) != OGRERR_NONE) fail(std::string("cannot add field ") + f.name);
  }
  if (out->StartTransaction() == OGRERR_FAILURE) fail("cannot start a transaction");
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const maps::Pathline& line = lines[k];
    if (line.t.empty()) continue;
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("pathline", static_cast<int>(k));
    if (sources && line.label && *line.label < about.source_names.size()) {
      feature.SetField("source", about.source_names[*line.label].c_str());
    }
    feature.SetField("start_time_s", line.t.front());
    feature.SetField("end_time_s", line.t.back());
    feature.SetField("fate", fate_name(line.fate));
    if (line.merged_into) feature.SetField("merged_into", static_cast<int>(*line.merged_into));
    feature.SetField("length_m", length_m(line));
    feature.SetField("vertices", static_cast<int>(line.t.size()));
    feature.SetField("time_units", about.time_units.c_str());
    std::vector<double> times = line.t;
    OGRLineString points;
    for (std::size_t v = 0; v < line.t.size(); ++v) {
      if (gpkg) {
        points.addPointM(line.x[v], line.y[v], line.t[v]);
      } else {
        points.addPoint(line.x[v], line.y[v]);
      }
    }
    if (line.t.size() == 1) {
      if (gpkg) {
        points.addPointM(line.x[0], line.y[0], line.t[0]);
      } else {
        points.addPoint(line.x[0], line.y[0]);
      }
      times.push_back(line.t[0]);
    }
    if (!gpkg) feature.SetField("time_s", static_cast<int>(times.size()), times.data());
    feature.SetGeometry(&points);
    if (layer->CreateFeature(&feature) != OGRERR_NONE) fail("cannot add a line");
  }
  if (out->CommitTransaction() == OGRERR_FAILURE) fail("cannot commit the lines");
  created.file.reset();  // closes, so that a failure to flush shows before the rename
  if (CPLGetLastErrorType() == CE_Failure) fail("cannot close it");
}

}  // namespace

void write_pathlines(const std::vector<maps::Pathline>& lines, const PathlineLayer& layer,
                     const std::filesystem::path& file, VectorFile format) {
  register_gdal_drivers();
  const QuietGdalErrors quiet;
  vector::write_then_rename(file, [&](const std::filesystem::path& partial) {
    write_layer(lines, layer, partial, format);
  });
}

}  // namespace swemps::io
