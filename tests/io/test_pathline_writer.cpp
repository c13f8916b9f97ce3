// Pathlines out (io/pathline_writer.hpp): GDAL reads them back as lines in the scene's CRS,
// time as each vertex's M in a GeoPackage and as a list attribute in GeoJSON.

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "swemps/io/gdal_messages.hpp"
#include "swemps/io/pathline_writer.hpp"

using swemps::io::PathlineLayer;
using swemps::io::VectorFile;
using swemps::io::write_pathlines;
using swemps::maps::Pathline;

namespace {

std::vector<Pathline> two_lines() {
  Pathline walked;
  walked.x = {500000.0, 500003.0, 500003.0};
  walked.y = {4000000.0, 4000000.0, 4000004.0};
  walked.t = {0.0, 10.0, 20.0};
  walked.label = 1;
  Pathline gone;  // chosen, then merged into the first line's particle in the same step
  gone.x = {500010.0};
  gone.y = {4000010.0};
  gone.t = {0.0};
  gone.label = 0;
  gone.fate = Pathline::Fate::merged;
  gone.merged_into = 0;
  return {walked, gone};
}

PathlineLayer utm_layer() {
  OGRSpatialReference utm;
  utm.importFromEPSG(32616);
  char* wkt = nullptr;
  utm.exportToWkt(&wkt);
  PathlineLayer layer;
  layer.crs_wkt = wkt;
  CPLFree(wkt);
  layer.source_names = {"lake", "river"};
  layer.time_units = "seconds since 2024-06-01 12:00:00";
  return layer;
}

GDALDatasetUniquePtr open_vector(const std::filesystem::path& file) {
  swemps::io::register_gdal_drivers();
  GDALDatasetUniquePtr ds(
      GDALDataset::Open(file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr));
  REQUIRE(ds);
  return ds;
}

}  // namespace

TEST_CASE("pathlines are a GeoPackage layer of measured lines in the scene's CRS",
          "[pathlines][io]") {
  swemps::testing::TempDir dir("pathlines");
  const auto file = dir.path() / "paths.gpkg";
  write_pathlines(two_lines(), utm_layer(), file, VectorFile::gpkg);
  CHECK_FALSE(std::filesystem::exists(dir.path() / "paths.partial.gpkg"));
  const auto ds = open_vector(file);
  OGRLayer* layer = ds->GetLayerByName("pathlines");
  REQUIRE(layer != nullptr);
  CHECK(layer->GetGeomType() == wkbLineStringM);
  REQUIRE(layer->GetFeatureCount() == 2);
  const OGRSpatialReference* crs = layer->GetSpatialRef();
  REQUIRE(crs != nullptr);
  CHECK(std::string(crs->GetAuthorityCode(nullptr)) == "32616");

  layer->ResetReading();
  OGRFeatureUniquePtr first(layer->GetNextFeature());
  REQUIRE(first);
  CHECK(first->GetFieldAsInteger("pathline") == 0);
  CHECK(std::string(first->GetFieldAsString("source")) == "river");
  CHECK(std::string(first->GetFieldAsString("fate")) == "in the domain");
  CHECK(first->GetFieldAsDouble("length_m") == Approx(7.0));
  CHECK(first->GetFieldAsDouble("end_time_s") == 20.0);
  CHECK(std::string(first->GetFieldAsString("time_units")) == "seconds since 2024-06-01 12:00:00");
  const OGRLineString* line = first->GetGeometryRef()->toLineString();
  REQUIRE(line->getNumPoints() == 3);
  CHECK(line->getX(1) == 500003.0);
  CHECK(line->getY(2) == 4000004.0);
  CHECK(line->getM(1) == 10.0);
  CHECK(line->getM(2) == 20.0);

  OGRFeatureUniquePtr second(layer->GetNextFeature());
  REQUIRE(second);
  CHECK(std::string(second->GetFieldAsString("fate")) == "merged");
  CHECK(second->GetFieldAsInteger("merged_into") == 0);
  CHECK_FALSE(first->IsFieldSetAndNotNull(first->GetFieldIndex("merged_into")));
  CHECK(second->GetFieldAsInteger("vertices") == 1);
  // One vertex, written twice: a line all the same.
  CHECK(second->GetGeometryRef()->toLineString()->getNumPoints() == 2);
}

TEST_CASE("pathlines in GeoJSON carry their vertices' times as a list", "[pathlines][io]") {
  swemps::testing::TempDir dir("pathlines");
  const auto file = dir.path() / "paths.geojson";
  PathlineLayer local;  // no CRS, no sources
  write_pathlines(two_lines(), local, file, VectorFile::geojson);
  const auto ds = open_vector(file);
  OGRLayer* layer = ds->GetLayer(0);
  REQUIRE(layer != nullptr);
  REQUIRE(layer->GetFeatureCount() == 2);
  CHECK(layer->GetLayerDefn()->GetFieldIndex("source") < 0);
  layer->ResetReading();
  OGRFeatureUniquePtr first(layer->GetNextFeature());
  REQUIRE(first);
  int n = 0;
  const double* times = first->GetFieldAsDoubleList("time_s", &n);
  REQUIRE(n == 3);
  CHECK(times[0] == 0.0);
  CHECK(times[2] == 20.0);
  const OGRLineString* line = first->GetGeometryRef()->toLineString();
  REQUIRE(line->getNumPoints() == 3);
  CHECK(line->getX(2) == 500003.0);
}

TEST_CASE("pathlines that cannot be written say which file", "[pathlines][io]") {
  swemps::testing::TempDir dir("pathlines");
  const auto file = dir.path() / "missing-folder" / "paths.gpkg";
  CHECK_THROWS_WITH(write_pathlines(two_lines(), utm_layer(), file, VectorFile::gpkg),
                    Catch::Matchers::Contains("paths"));
}
