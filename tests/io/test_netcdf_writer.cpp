#include <gdal_priv.h>
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/particles/swe_particles.hpp"

namespace fs = std::filesystem;
using swemps::io::BalanceSample;
using swemps::io::Gauge;
using swemps::io::GaugeSample;
using swemps::io::Grid;
using swemps::io::Layout;
using swemps::io::MapFields;
using swemps::io::NetcdfWriter;
using swemps::io::RunMetadata;
using swemps::maps::FloodStatistics;
using swemps::particles::SweParticles;

using TempDir = swemps::testing::TempDir;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

fs::path partial_of(const fs::path& p) {
  fs::path q = p;
  q += ".partial";
  return q;
}

Grid small_grid() {
  Grid g;
  g.x0 = 10.0;
  g.y0 = -5.0;
  g.dx = 2.0;
  g.dy = 0.5;
  g.nx = 4;
  g.ny = 3;
  return g;
}

RunMetadata metadata() {
  RunMetadata m;
  m.title = "unit test run";
  m.scenario_file = "cases/dam_break.toml";
  m.history = "swe-mps run cases/dam_break.toml";
  m.gravity_m_s2 = 9.80665;
  return m;
}

// Particle i of record r has distinct values per field so misplaced slabs are detected.
SweParticles make_particles(int n, int record) {
  SweParticles p;
  for (int i = 0; i < n; ++i) {
    const double b = 1000.0 * record + 10.0 * i;
    p.add_fluid(b + 1, b + 2, b + 3, b + 4, b + 5, b + 6, b + 7, b + 8);
  }
  return p;
}

// Thin read-side helpers: any failure of the reader fails the test with netCDF's message.
void nc_ok(int status) {
  INFO(nc_strerror(status));
  REQUIRE(status == NC_NOERR);
}

class Reader {
 public:
  explicit Reader(const fs::path& p) { nc_ok(nc_open(p.c_str(), NC_NOWRITE, &ncid_)); }
  ~Reader() { nc_close(ncid_); }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  int var(const char* name) const {
    int id = -1;
    INFO("variable " << name);
    nc_ok(nc_inq_varid(ncid_, name, &id));
    return id;
  }
  bool has_var(const char* name) const {
    int id = -1;
    return nc_inq_varid(ncid_, name, &id) == NC_NOERR;
  }
  bool has_dim(const char* name) const {
    int id = -1;
    return nc_inq_dimid(ncid_, name, &id) == NC_NOERR;
  }
  std::size_t dim(const char* name) const {
    int id = -1;
    INFO("dimension " << name);
    nc_ok(nc_inq_dimid(ncid_, name, &id));
    std::size_t len = 0;
    nc_ok(nc_inq_dimlen(ncid_, id, &len));
    return len;
  }
  // Text attribute of variable `var_name`, or a global one when var_name is null.
  std::string text(const char* var_name, const char* att) const {
    const int varid = var_name ? var(var_name) : NC_GLOBAL;
    std::size_t len = 0;
    INFO("attribute " << att);
    nc_ok(nc_inq_attlen(ncid_, varid, att, &len));
    std::string value(len, '\0');
    nc_ok(nc_get_att_text(ncid_, varid, att, value.data()));
    return value;
  }
  bool has_att(const char* var_name, const char* att) const {
    const int varid = var_name ? var(var_name) : NC_GLOBAL;
    int attid = -1;
    return nc_inq_attid(ncid_, varid, att, &attid) == NC_NOERR;
  }
  std::vector<double> doubles(const char* name, std::size_t start, std::size_t count) const {
    std::vector<double> v(count);
    nc_ok(nc_get_vara_double(ncid_, var(name), &start, &count, v.data()));
    return v;
  }
  std::vector<std::string> dim_names(const char* name) const {
    const int id = var(name);
    int ndims = 0;
    nc_ok(nc_inq_varndims(ncid_, id, &ndims));
    std::vector<int> dims(static_cast<std::size_t>(ndims));
    nc_ok(nc_inq_vardimid(ncid_, id, dims.data()));
    std::vector<std::string> names;
    for (const int d : dims) {
      std::array<char, NC_MAX_NAME + 1> dim_name{};
      nc_ok(nc_inq_dimname(ncid_, d, dim_name.data()));
      names.emplace_back(dim_name.data());
    }
    return names;
  }
  std::size_t length(const char* name) const {
    std::size_t n = 1;
    for (const std::string& d : dim_names(name)) n *= dim(d.c_str());
    return n;
  }
  std::vector<float> floats(const char* name) const {
    std::vector<float> v(length(name));
    nc_ok(nc_get_var_float(ncid_, var(name), v.data()));
    return v;
  }
  std::vector<double> all_doubles(const char* name) const {
    std::vector<double> v(length(name));
    nc_ok(nc_get_var_double(ncid_, var(name), v.data()));
    return v;
  }
  std::vector<std::string> strings(const char* name) const {
    std::vector<char*> raw(length(name));
    nc_ok(nc_get_var_string(ncid_, var(name), raw.data()));
    std::vector<std::string> out(raw.begin(), raw.end());
    nc_free_string(raw.size(), raw.data());
    return out;
  }
  // Numeric attribute values of variable `var_name` (global when null), as doubles.
  std::vector<double> numbers(const char* var_name, const char* att) const {
    const int varid = var_name ? var(var_name) : NC_GLOBAL;
    std::size_t len = 0;
    INFO("attribute " << att);
    nc_ok(nc_inq_attlen(ncid_, varid, att, &len));
    std::vector<double> v(len);
    nc_ok(nc_get_att_double(ncid_, varid, att, v.data()));
    return v;
  }
  // Whether the variable is stored with shuffle and deflate at `level`.
  bool compressed(const char* name, int level) const {
    int shuffle = 0, deflate = 0, deflate_level = 0;
    nc_ok(nc_inq_var_deflate(ncid_, var(name), &shuffle, &deflate, &deflate_level));
    return shuffle == 1 && deflate == 1 && deflate_level == level;
  }
  int ncid() const { return ncid_; }

 private:
  int ncid_ = -1;
};

bool on_path(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

// The four map fields of one output time, with values distinct per field and cell so that
// a field written in the place of another is detected.
struct Maps {
  std::vector<double> depth, surface, u, v;
  MapFields fields() const { return {depth, surface, u, v}; }
};

Maps make_maps(std::size_t cells, double offset) {
  Maps m;
  for (std::size_t i = 0; i < cells; ++i) {
    const double d = offset + 0.25 * static_cast<double>(i);
    m.depth.push_back(d);
    m.surface.push_back(100.0 + d);
    m.u.push_back(-0.5 * d);
    m.v.push_back(2.0 + d);
  }
  return m;
}

Layout layout_of(const Grid& grid, bool particles, std::vector<Gauge> gauges = {}) {
  return Layout{grid, particles, std::move(gauges)};
}

// WKT of a UTM zone, as a caller would take it from its terrain raster.
std::string utm_wkt(int epsg) { return swemps::testing::wkt_of("EPSG:" + std::to_string(epsg)); }

Grid utm_grid() {
  Grid g;
  g.x0 = 641235.5;
  g.y0 = 4123456.25;
  g.dx = 5.0;
  g.dy = 2.5;
  g.nx = 4;
  g.ny = 3;
  g.crs_wkt = utm_wkt(32616);
  return g;
}

// Statistics with a known pattern: cell 0 never has data, cell 1 is never wet, the others
// flood at the second sample.
FloodStatistics make_statistics(std::size_t cells) {
  FloodStatistics stats(cells, {0.05, {0.25}});
  std::vector<double> dry(cells, 0.01), wet(cells), u(cells, 1.0), v(cells, 0.0);
  for (std::size_t i = 0; i < cells; ++i) wet[i] = 0.1 * static_cast<double>(i);
  dry[0] = wet[0] = kNaN;
  wet[1] = 0.02;
  stats.update(0.0, dry, u, v);
  stats.update(4.0, wet, u, v);
  stats.update(10.0, wet, u, v);
  return stats;
}

// Output of a shell command, for the command-line readers.
std::string capture(const std::string& command) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe.get()) != nullptr) out += buffer.data();
  return out;
}

}  // namespace

TEST_CASE("NetcdfWriter writes a CF file under a temporary name", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "run.nc";
  const Grid grid = small_grid();
  const std::size_t cells = grid.nx * grid.ny;

  const SweParticles p0 = make_particles(3, 0);
  SweParticles p1 = make_particles(5, 1);
  p1.add_ghost(0, -1, -1, -1, -1);  // ghosts must not reach the file
  const Maps m0 = make_maps(cells, 0.0);
  Maps m1 = make_maps(cells, 1.0);
  // No data in one cell of each field, stored as the fill value.
  m1.depth[2] = m1.surface[3] = m1.u[4] = m1.v[5] = kNaN;

  {
    NetcdfWriter w(file, layout_of(grid, true), metadata());
    CHECK(w.path() == file);
    w.write(0.0, p0, m0.fields());
    w.write(2.5, p1, m1.fields());
    CHECK(w.records() == 2);
    CHECK(fs::exists(partial_of(file)));
    CHECK_FALSE(fs::exists(file));
    w.finish();
    CHECK(fs::exists(file));
    CHECK_FALSE(fs::exists(partial_of(file)));
    CHECK_THROWS_AS(w.finish(), std::logic_error);
    CHECK_THROWS_AS(w.write(5.0, p0, m0.fields()), std::logic_error);
    CHECK_THROWS_AS(w.write_series(5.0, {}, BalanceSample{}), std::logic_error);
    CHECK_THROWS_AS(w.write_bed(m0.depth), std::logic_error);
    CHECK_THROWS_AS(w.write_summary(FloodStatistics(cells, {0.01})), std::logic_error);
  }
  CHECK(fs::exists(file));  // the destructor of a finished writer leaves the file alone

  Reader r(file);
  SECTION("global attributes") {
    CHECK(r.text(nullptr, "Conventions") == "CF-1.8");
    CHECK(r.text(nullptr, "title") == "unit test run");
    CHECK(r.text(nullptr, "source") == "cases/dam_break.toml");
    CHECK(r.text(nullptr, "history") == "swe-mps run cases/dam_break.toml");
    CHECK(r.text(nullptr, "references") == "swe-mps shallow-water MPS");
    CHECK_FALSE(r.has_att(nullptr, "featureType"));
    CHECK(r.numbers(nullptr, "gravity_m_s2") == std::vector<double>{9.80665});
  }
  SECTION("dimensions and coordinates") {
    CHECK(r.dim("time") == 2);
    CHECK(r.dim("y") == 3);
    CHECK(r.dim("x") == 4);
    CHECK(r.dim("particle_sample") == 8);
    CHECK(r.dim("series_time") == 0);
    CHECK(r.doubles("x", 0, 4) == std::vector<double>{10.0, 12.0, 14.0, 16.0});
    CHECK(r.doubles("y", 0, 3) == std::vector<double>{-5.0, -4.5, -4.0});
    CHECK(r.doubles("time", 0, 2) == std::vector<double>{0.0, 2.5});
    CHECK(r.text("time", "units") == "seconds since 1970-01-01 00:00:00");
    CHECK(r.text("time", "calendar") == "standard");
    CHECK(r.text("time", "axis") == "T");
    CHECK(r.text("x", "standard_name") == "projection_x_coordinate");
    CHECK(r.text("y", "standard_name") == "projection_y_coordinate");
    CHECK(r.text("x", "axis") == "X");
    CHECK(r.text("y", "axis") == "Y");
    CHECK(r.text("x", "units") == "m");
    CHECK(r.text("y", "units") == "m");
  }
  SECTION("maps per output time") {
    CHECK(r.text("depth", "standard_name") == "flood_water_thickness");
    CHECK_FALSE(r.has_var("crs"));
    const struct {
      const char* name;
      const char* units;
      const std::vector<double>& first;
      const std::vector<double>& second;
    } maps[] = {{"depth", "m", m0.depth, m1.depth},
                {"surface_elevation", "m", m0.surface, m1.surface},
                {"u", "m s-1", m0.u, m1.u},
                {"v", "m s-1", m0.v, m1.v}};
    for (const auto& m : maps) {
      INFO("variable " << m.name);
      CHECK(r.text(m.name, "units") == m.units);
      CHECK(r.has_att(m.name, "long_name"));
      CHECK_FALSE(r.has_att(m.name, "grid_mapping"));  // no CRS, no grid mapping
      CHECK(r.dim_names(m.name) == std::vector<std::string>{"time", "y", "x"});
      CHECK(r.compressed(m.name, 4));
      nc_type type = NC_NAT;
      nc_ok(nc_inq_vartype(r.ncid(), r.var(m.name), &type));
      CHECK(type == NC_FLOAT);
      CHECK(r.numbers(m.name, "_FillValue") == std::vector<double>{NC_FILL_FLOAT});
      // One chunk per time slice.
      int storage = -1;
      std::array<std::size_t, 3> chunk{};
      nc_ok(nc_inq_var_chunking(r.ncid(), r.var(m.name), &storage, chunk.data()));
      CHECK(chunk == std::array<std::size_t, 3>{1, 3, 4});

      const std::vector<float> all = r.floats(m.name);
      REQUIRE(all.size() == 2 * cells);
      for (std::size_t i = 0; i < cells; ++i) {
        CHECK(all[i] == static_cast<float>(m.first[i]));
        if (std::isnan(m.second[i])) {
          CHECK(all[cells + i] == NC_FILL_FLOAT);
        } else {
          CHECK(all[cells + i] == static_cast<float>(m.second[i]));
        }
      }
    }
  }
  SECTION("particles as a contiguous ragged array") {
    CHECK(r.text("particle_count", "sample_dimension") == "particle_sample");
    std::array<int, 2> counts{};
    nc_ok(nc_get_var_int(r.ncid(), r.var("particle_count"), counts.data()));
    CHECK(counts == std::array<int, 2>{3, 5});

    // Record 2 starts after the samples of record 1.
    const std::size_t offset = static_cast<std::size_t>(counts[0]);
    const std::size_t n = static_cast<std::size_t>(counts[1]);
    CHECK(r.doubles("particle_x", offset, n) ==
          std::vector<double>(p1.x.begin(), p1.x.begin() + 5));
    CHECK(r.doubles("particle_y", offset, n) ==
          std::vector<double>(p1.y.begin(), p1.y.begin() + 5));
    CHECK(r.doubles("particle_u", offset, n) ==
          std::vector<double>(p1.u.begin(), p1.u.begin() + 5));
    CHECK(r.doubles("particle_v", offset, n) ==
          std::vector<double>(p1.v.begin(), p1.v.begin() + 5));
    CHECK(r.doubles("particle_depth", offset, n) ==
          std::vector<double>(p1.depth.begin(), p1.depth.begin() + 5));
    CHECK(r.doubles("particle_volume", offset, n) ==
          std::vector<double>(p1.volume.begin(), p1.volume.begin() + 5));
    CHECK(r.doubles("particle_area", offset, n) ==
          std::vector<double>(p1.area.begin(), p1.area.begin() + 5));
    CHECK(r.doubles("particle_x", 0, 3) == p0.x);
    CHECK(r.text("particle_u", "units") == "m s-1");
    CHECK(r.text("particle_volume", "units") == "m3");
    CHECK(r.text("particle_area", "units") == "m2");
    for (const char* name : {"particle_x", "particle_y", "particle_u", "particle_v",
                             "particle_depth", "particle_volume", "particle_area"}) {
      INFO("variable " << name);
      CHECK(r.compressed(name, 1));
    }
  }
  SECTION("variables written once are absent when never written") {
    for (const char* name :
         {"bed_elevation", "max_depth", "max_speed", "max_depth_speed", "max_hazard_rating",
          "hazard_class_uk", "hazard_class_aidr", "arrival_time", "inundation_duration"}) {
      INFO("variable " << name);
      CHECK_FALSE(r.has_var(name));
    }
  }
}

TEST_CASE("NetcdfWriter output opens in common command-line readers", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "tools.nc";
  const Grid grid = utm_grid();
  const std::size_t cells = grid.nx * grid.ny;
  {
    NetcdfWriter w(file, layout_of(grid, true, {{"bridge", grid.x0, grid.y0}}), metadata());
    w.write(1.0, make_particles(2, 0), make_maps(cells, 0.5).fields());
    w.write_series(1.0, std::vector<GaugeSample>{{0.5, 1.0, 0.0}}, BalanceSample{});
    w.write_bed(make_maps(cells, 3.0).surface);
    w.write_summary(make_statistics(cells));
    w.finish();
  }
  const std::string quiet = " >/dev/null 2>&1";
  if (on_path("ncdump")) {
    CHECK(std::system(("ncdump -h \"" + file.string() + "\"" + quiet).c_str()) == 0);
  } else {
    WARN("ncdump not found; header dump not checked");
  }
  if (on_path("gdalinfo")) {
    const std::string info = capture("gdalinfo 'NETCDF:\"" + file.string() + "\":max_depth' 2>&1");
    INFO(info);
    CHECK(info.find("Size is 4, 3") != std::string::npos);
    CHECK(info.find("ID[\"EPSG\",32616]") != std::string::npos);
  } else {
    WARN("gdalinfo not found; raster reading not checked");
  }
}

TEST_CASE("NetcdfWriter georeferences the grid for GDAL", "[io][netcdf][crs]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "utm.nc";
  const Grid grid = utm_grid();
  const std::size_t cells = grid.nx * grid.ny;
  {
    NetcdfWriter w(file, layout_of(grid, false, {{"g1", grid.x0, grid.y0}}), metadata());
    w.write(0.0, SweParticles{}, make_maps(cells, 0.0).fields());
    w.write_bed(make_maps(cells, 3.0).surface);
    w.write_summary(make_statistics(cells));
    w.finish();
  }
  const std::array<double, 6> expected{grid.x0 - 0.5 * grid.dx,
                                       grid.dx,
                                       0.0,
                                       grid.y0 + (static_cast<double>(grid.ny) - 0.5) * grid.dy,
                                       0.0,
                                       -grid.dy};

  SECTION("CF grid mapping and GDAL attributes") {
    Reader r(file);
    CHECK(r.text("crs", "grid_mapping_name") == "transverse_mercator");
    CHECK(r.numbers("crs", "longitude_of_central_meridian") == std::vector<double>{-87.0});
    CHECK(r.numbers("crs", "scale_factor_at_central_meridian") == std::vector<double>{0.9996});
    CHECK(r.numbers("crs", "latitude_of_projection_origin") == std::vector<double>{0.0});
    CHECK(r.numbers("crs", "false_easting") == std::vector<double>{500000.0});
    CHECK(r.numbers("crs", "false_northing") == std::vector<double>{0.0});
    CHECK(r.numbers("crs", "semi_major_axis") == std::vector<double>{6378137.0});
    CHECK(r.numbers("crs", "inverse_flattening")[0] == Approx(298.257223563));
    CHECK(r.text("crs", "projected_crs_name") == "WGS 84 / UTM zone 16N");
    CHECK(r.text("crs", "crs_wkt") == r.text("crs", "spatial_ref"));
    // The WKT written reads back as the CRS given.
    OGRSpatialReference given, written;
    REQUIRE(given.importFromWkt(grid.crs_wkt.c_str()) == OGRERR_NONE);
    REQUIRE(written.importFromWkt(r.text("crs", "crs_wkt").c_str()) == OGRERR_NONE);
    CHECK(written.IsSame(&given));

    std::array<double, 6> transform{};
    const std::string text = r.text("crs", "GeoTransform");
    REQUIRE(std::sscanf(text.c_str(), "%lf %lf %lf %lf %lf %lf", &transform[0], &transform[1],
                        &transform[2], &transform[3], &transform[4], &transform[5]) == 6);
    CHECK(transform == expected);

    for (const char* name :
         {"depth", "surface_elevation", "u", "v", "bed_elevation", "max_depth", "max_speed",
          "max_depth_speed", "arrival_time", "inundation_duration", "hazard_class_uk",
          "gauge_surface_elevation", "gauge_depth", "gauge_u", "gauge_v"}) {
      INFO("variable " << name);
      CHECK(r.text(name, "grid_mapping") == "crs");
    }
  }

  SECTION("GDAL reads the same CRS and geotransform") {
    GDALAllRegister();
    const std::string name = "NETCDF:\"" + file.string() + "\":max_depth";
    std::unique_ptr<GDALDataset> ds(GDALDataset::FromHandle(GDALOpen(name.c_str(), GA_ReadOnly)));
    REQUIRE(ds != nullptr);
    CHECK(ds->GetRasterXSize() == 4);
    CHECK(ds->GetRasterYSize() == 3);

    std::array<double, 6> transform{};
    REQUIRE(ds->GetGeoTransform(transform.data()) == CE_None);
    for (std::size_t k = 0; k < 6; ++k) {
      INFO("geotransform term " << k);
      CHECK(transform[k] == Approx(expected[k]).epsilon(1e-9).margin(1e-12));
    }

    const OGRSpatialReference* srs = ds->GetSpatialRef();
    REQUIRE(srs != nullptr);
    OGRSpatialReference utm;
    REQUIRE(utm.importFromEPSG(32616) == OGRERR_NONE);
    CHECK(srs->IsSame(&utm));
    REQUIRE(srs->GetAuthorityCode(nullptr) != nullptr);
    CHECK(std::string(srs->GetAuthorityCode(nullptr)) == "32616");

    // North-up: the first row GDAL returns is the top (largest y) row of the grid.
    std::vector<float> top(4);
    REQUIRE(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 4, 1, top.data(), 4, 1, GDT_Float32, 0,
                                           0) == CE_None);
    Reader r(file);
    const std::vector<float> stored = r.floats("max_depth");
    for (std::size_t i = 0; i < 4; ++i) CHECK(top[i] == stored[8 + i]);
    int has_nodata = 0;
    CHECK(ds->GetRasterBand(1)->GetNoDataValue(&has_nodata) == Approx(NC_FILL_FLOAT));
    CHECK(has_nodata == 1);
  }
}

TEST_CASE("NetcdfWriter rejects a CRS that is not projected in metres", "[io][netcdf][crs]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "bad_crs.nc";
  const auto rejects = [&](const std::string& wkt) {
    Grid grid = small_grid();
    grid.crs_wkt = wkt;
    try {
      NetcdfWriter w(file, layout_of(grid, false), metadata());
      FAIL("expected std::invalid_argument");
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find(file.string()) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(file));
    CHECK_FALSE(fs::exists(partial_of(file)));
  };
  rejects("not a CRS");
  rejects(utm_wkt(4326));  // geographic: degrees
  rejects(utm_wkt(2227));  // California zone 3 in US survey feet
}

TEST_CASE("NetcdfWriter writes the bed once", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "bed.nc";
  const Grid grid = small_grid();
  const std::size_t cells = grid.nx * grid.ny;
  std::vector<double> bed = make_maps(cells, 7.0).surface;
  bed[1] = kNaN;
  {
    NetcdfWriter w(file, layout_of(grid, false), metadata());
    CHECK_THROWS_AS(w.write_bed(std::vector<double>(cells + 1, 0.0)), std::invalid_argument);
    w.write_bed(bed);
    CHECK_THROWS_AS(w.write_bed(bed), std::logic_error);
    // Records can follow the bed: the file layout is not frozen by a late variable.
    w.write(0.0, SweParticles{}, make_maps(cells, 0.0).fields());
    w.finish();
  }
  Reader r(file);
  CHECK(r.dim("time") == 1);
  CHECK(r.dim_names("bed_elevation") == std::vector<std::string>{"y", "x"});
  CHECK(r.text("bed_elevation", "units") == "m");
  CHECK(r.text("bed_elevation", "standard_name") == "surface_altitude");
  CHECK(r.compressed("bed_elevation", 4));
  const std::vector<float> stored = r.floats("bed_elevation");
  for (std::size_t i = 0; i < cells; ++i) {
    CHECK(stored[i] == (i == 1 ? NC_FILL_FLOAT : static_cast<float>(bed[i])));
  }
}

TEST_CASE("NetcdfWriter writes the whole-run summary maps", "[io][netcdf][summary]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "summary.nc";
  const Grid grid = small_grid();
  const std::size_t cells = grid.nx * grid.ny;
  const FloodStatistics stats = make_statistics(cells);
  {
    NetcdfWriter w(file, layout_of(grid, false), metadata());
    w.write(0.0, SweParticles{}, make_maps(cells, 0.0).fields());
    CHECK_THROWS_AS(w.write_summary(FloodStatistics(cells - 1, {0.05})), std::invalid_argument);
    w.write_summary(stats);
    CHECK_THROWS_AS(w.write_summary(stats), std::logic_error);
    w.finish();
  }
  Reader r(file);
  const struct {
    const char* name;
    std::span<const double> values;
    const char* units;
  } summary[] = {{"max_depth", stats.max_depth(), "m"},
                 {"time_of_max_depth", stats.time_of_max_depth(), "s"},
                 {"max_surface_elevation", stats.max_surface_elevation(), "m"},
                 {"max_speed", stats.max_speed(), "m s-1"},
                 {"max_depth_speed", stats.max_depth_speed(), "m2 s-1"},
                 {"max_depth_speed2", stats.max_depth_speed2(), "m3 s-2"},
                 {"max_hazard_rating", stats.max_hazard_rating(), "1"}};
  const auto check_stored = [&](const std::vector<float>& stored, std::span<const double> values) {
    REQUIRE(stored.size() == values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      INFO("cell " << i);
      if (std::isnan(values[i])) {
        CHECK(stored[i] == NC_FILL_FLOAT);
      } else {
        CHECK(stored[i] == static_cast<float>(values[i]));
      }
    }
  };
  for (const auto& s : summary) {
    INFO("variable " << s.name);
    CHECK(r.dim_names(s.name) == std::vector<std::string>{"y", "x"});
    CHECK(r.text(s.name, "units") == s.units);
    CHECK(r.compressed(s.name, 4));
    CHECK(r.numbers(s.name, "_FillValue") == std::vector<double>{NC_FILL_FLOAT});
    CHECK(r.numbers(s.name, "wet_depth_threshold_m") == std::vector<double>{0.05});
    CHECK(r.numbers(s.name, "sample_count") == std::vector<double>{3.0});
    if (std::string(s.name) != "max_depth") {  // the only one that does not depend on it
      CHECK(r.text(s.name, "comment").find("depth > 0.05 m") != std::string::npos);
    }
    check_stored(r.floats(s.name), s.values);
  }
  CHECK(r.text("max_depth", "standard_name") == "flood_water_thickness");
  CHECK(r.text("max_depth", "cell_methods") == "time: maximum");
  CHECK(r.text("max_hazard_rating", "long_name").find("HR = d (v + 0.5) + DF") !=
        std::string::npos);
  CHECK(r.text("max_hazard_rating", "comment").find("urban") != std::string::npos);
  CHECK(r.text("inundation_duration", "comment").find("(t_{k-1}, t_k]") != std::string::npos);

  // One map per depth threshold: the wet depth, then the scene's further ones.
  CHECK(r.all_doubles("depth_threshold") == std::vector<double>{0.05, 0.25});
  for (const char* name : {"arrival_time", "inundation_duration"}) {
    INFO("variable " << name);
    CHECK(r.dim_names(name) == std::vector<std::string>{"depth_threshold", "y", "x"});
    const std::vector<float> stored = r.floats(name);
    REQUIRE(stored.size() == 2 * cells);
    const bool arrival = std::string(name) == "arrival_time";
    for (std::size_t j = 0; j < 2; ++j) {
      check_stored({stored.begin() + static_cast<long>(j * cells),
                    stored.begin() + static_cast<long>((j + 1) * cells)},
                   arrival ? stats.arrival_time(j) : stats.duration_above(j));
    }
  }
  // The pattern of make_statistics: no data, never wet, and wet from t = 4 s to 10 s; cells
  // 3 and up are 0.3 m and deeper, above 0.25 m.
  const std::vector<float> arrival = r.floats("arrival_time");
  const std::vector<float> duration = r.floats("inundation_duration");
  CHECK(arrival[0] == NC_FILL_FLOAT);
  CHECK(arrival[1] == NC_FILL_FLOAT);
  CHECK(duration[1] == 0.0f);
  CHECK(arrival[5] == 4.0f);
  CHECK(duration[5] == 10.0f);
  CHECK(arrival[cells + 2] == NC_FILL_FLOAT);  // 0.2 m
  CHECK(arrival[cells + 3] == 4.0f);

  // Hazard classes as CF flags: 0 never wet, the fill value where no data.
  for (const char* name : {"hazard_class_uk", "hazard_class_aidr"}) {
    INFO("variable " << name);
    CHECK(r.dim_names(name) == std::vector<std::string>{"y", "x"});
    CHECK(r.text(name, "flag_meanings").rfind("not_flooded ", 0) == 0);
  }
  CHECK(r.text("hazard_class_aidr", "flag_meanings") == "not_flooded H1 H2 H3 H4 H5 H6");
  const std::vector<double> uk = r.all_doubles("hazard_class_uk");
  const std::vector<double> aidr = r.all_doubles("hazard_class_aidr");
  CHECK(uk[0] == 255.0);
  CHECK(uk[1] == 0.0);
  CHECK(aidr[1] == 0.0);
  // Cell 5: 0.5 m at 1 m/s: HR = 0.5 x 1.5 + 1 (urban, 0.25-0.75 m) = 1.75, significant;
  // d v = 0.5 within H2's 0.6 and d = 0.5 within its 0.5 m.
  CHECK(uk[5] == 3.0);
  CHECK(aidr[5] == 2.0);
}

TEST_CASE("NetcdfWriter writes gauge and volume-balance series", "[io][netcdf][series]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "series.nc";
  const Grid grid = small_grid();
  const std::size_t cells = grid.nx * grid.ny;
  const std::vector<Gauge> gauges{{"upstream", 10.5, -4.75}, {"bridge", 15.0, -4.0}};
  const std::vector<GaugeSample> s0{{0.25, 1.5, -0.5}, {kNaN, kNaN, kNaN}};
  const std::vector<GaugeSample> s1{{0.5, 2.0, 0.25}, {0.125, 0.75, 0.0}};
  const BalanceSample b0{100.0, 0.0, 0.0, 0.0, 0.0};
  const BalanceSample b1{106.5, 5.0, 2.5, 1.0, -1e-12};
  {
    NetcdfWriter w(file, layout_of(grid, false, gauges), metadata());
    CHECK_THROWS_AS(w.write_series(0.0, std::vector<GaugeSample>(1), b0), std::invalid_argument);
    w.write_series(0.0, s0, b0);
    w.write(0.0, SweParticles{}, make_maps(cells, 0.0).fields());
    w.write_series(0.5, s1, b1);
    w.write_series(1.0, s1, b1);
    CHECK(w.series_records() == 3);
    CHECK(w.records() == 1);
    w.finish();
  }
  Reader r(file);
  CHECK(r.dim("series_time") == 3);
  CHECK(r.dim("time") == 1);  // the map axis is separate
  CHECK(r.dim("gauge") == 2);
  CHECK(r.all_doubles("series_time") == std::vector<double>{0.0, 0.5, 1.0});
  CHECK(r.text("series_time", "units") == "seconds since 1970-01-01 00:00:00");
  CHECK(r.text("series_time", "standard_name") == "time");

  CHECK(r.strings("gauge_name") == std::vector<std::string>{"upstream", "bridge"});
  CHECK(r.text("gauge_name", "cf_role") == "timeseries_id");
  CHECK(r.all_doubles("gauge_x") == std::vector<double>{10.5, 15.0});
  CHECK(r.all_doubles("gauge_y") == std::vector<double>{-4.75, -4.0});
  CHECK(r.text("gauge_x", "standard_name") == "projection_x_coordinate");

  const double fill = NC_FILL_DOUBLE;
  CHECK(r.dim_names("gauge_depth") == std::vector<std::string>{"series_time", "gauge"});
  CHECK(r.text("gauge_depth", "coordinates") == "gauge_x gauge_y gauge_name");
  CHECK_FALSE(r.has_att("gauge_depth", "grid_mapping"));
  CHECK(r.all_doubles("gauge_depth") == std::vector<double>{0.25, fill, 0.5, 0.125, 0.5, 0.125});
  CHECK(r.all_doubles("gauge_u") == std::vector<double>{1.5, fill, 2.0, 0.75, 2.0, 0.75});
  CHECK(r.all_doubles("gauge_v") == std::vector<double>{-0.5, fill, 0.25, 0.0, 0.25, 0.0});
  CHECK(r.text("gauge_u", "units") == "m s-1");

  CHECK(r.all_doubles("volume_in_domain") == std::vector<double>{100.0, 106.5, 106.5});
  CHECK(r.all_doubles("volume_inflow") == std::vector<double>{0.0, 5.0, 5.0});
  CHECK(r.all_doubles("volume_rain") == std::vector<double>{0.0, 2.5, 2.5});
  CHECK(r.all_doubles("volume_outflow") == std::vector<double>{0.0, 1.0, 1.0});
  CHECK(r.all_doubles("volume_error") == std::vector<double>{0.0, -1e-12, -1e-12});
  CHECK(r.text("volume_in_domain", "units") == "m3");
  CHECK(r.text("volume_error", "units") == "1");
  for (const char* name : {"gauge_depth", "gauge_u", "gauge_v", "volume_in_domain", "volume_inflow",
                           "volume_rain", "volume_outflow", "volume_error"}) {
    INFO("variable " << name);
    CHECK(r.compressed(name, 4));
    CHECK(r.numbers(name, "_FillValue") == std::vector<double>{fill});
  }
}

TEST_CASE("NetcdfWriter without gauges defines no gauge variables", "[io][netcdf][series]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "no_gauges.nc";
  {
    NetcdfWriter w(file, layout_of(small_grid(), false), metadata());
    w.write_series(0.0, {}, BalanceSample{1.0, 0.0, 0.0, 0.0, 0.0});
    w.finish();
  }
  Reader r(file);
  CHECK(r.dim("series_time") == 1);
  CHECK_FALSE(r.has_dim("gauge"));
  CHECK_FALSE(r.has_var("gauge_name"));
  CHECK_FALSE(r.has_var("gauge_depth"));
  CHECK(r.all_doubles("volume_in_domain") == std::vector<double>{1.0});
}

TEST_CASE("NetcdfWriter rejects unnamed or repeated gauges", "[io][netcdf][series]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "bad_gauges.nc";
  const Grid grid = small_grid();
  CHECK_THROWS_AS(NetcdfWriter(file, layout_of(grid, false, {{"", 0.0, 0.0}}), metadata()),
                  std::invalid_argument);
  CHECK_THROWS_AS(
      NetcdfWriter(file, layout_of(grid, false, {{"a", 0.0, 0.0}, {"a", 1.0, 1.0}}), metadata()),
      std::invalid_argument);
  CHECK_THROWS_AS(NetcdfWriter(file, layout_of(grid, false, {{"a", kNaN, 0.0}}), metadata()),
                  std::invalid_argument);
  CHECK_FALSE(fs::exists(partial_of(file)));
}

TEST_CASE("NetcdfWriter output opens in xarray", "[io][netcdf][python]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "xarray.nc";
  const Grid grid = utm_grid();
  const std::size_t cells = grid.nx * grid.ny;
  {
    NetcdfWriter w(file, layout_of(grid, true, {{"g1", grid.x0, grid.y0}}), metadata());
    w.write(0.0, make_particles(2, 0), make_maps(cells, 0.0).fields());
    w.write(1.0, make_particles(3, 1), make_maps(cells, 1.0).fields());
    w.write_series(0.5, std::vector<GaugeSample>{{0.5, 1.0, 0.0}}, BalanceSample{});
    w.write_bed(make_maps(cells, 3.0).surface);
    w.write_summary(make_statistics(cells));
    w.finish();
  }
  // The script prints nothing and exits 0 when every property holds; an assertion
  // failure or a missing xarray makes it exit non-zero with the reason on stderr.
  const std::string script =
      "import sys, numpy as np, xarray\n"
      "ds = xarray.open_dataset(sys.argv[1])\n"
      "assert ds['max_depth'].dims == ('y', 'x'), ds['max_depth'].dims\n"
      "assert ds['depth'].dims == ('time', 'y', 'x'), ds['depth'].dims\n"
      "assert ds['gauge_depth'].dims == ('series_time', 'gauge'), ds['gauge_depth'].dims\n"
      "assert list(ds['gauge_name'].values) == ['g1'], ds['gauge_name'].values\n"
      "assert ds['arrival_time'].dims == ('depth_threshold', 'y', 'x'), ds['arrival_time'].dims\n"
      "arrival = ds['arrival_time'].sel(depth_threshold=0.05)\n"
      "assert np.isnan(arrival.values[0, 0])\n"
      "assert float(arrival.values[1, 1]) == 4.0\n"
      "assert int(ds['hazard_class_aidr'].values[1, 1]) == 2, ds['hazard_class_aidr'].values\n"
      "assert ds['depth'].sizes['time'] == 2 and ds['x'].size == 4 and ds['y'].size == 3\n"
      "assert 'crs_wkt' in ds['crs'].attrs\n";
  const fs::path script_file = tmp.path() / "check.py";
  std::ofstream(script_file) << script;
  const std::string command =
      "/usr/bin/python3 \"" + script_file.string() + "\" \"" + file.string() + "\" 2>&1";
  const std::string output = capture(command + "; echo \"exit $?\"");
  INFO(output);
  CHECK(output.find("exit 0") != std::string::npos);
}

TEST_CASE("NetcdfWriter without particles defines no particle variables", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "grid_only.nc";
  const Grid grid = small_grid();
  {
    NetcdfWriter w(file, layout_of(grid, false), metadata());
    w.write(0.0, make_particles(2, 0), make_maps(grid.nx * grid.ny, 0.0).fields());
    w.finish();
  }
  Reader r(file);
  CHECK(r.dim("time") == 1);
  CHECK_FALSE(r.has_dim("particle_sample"));
  CHECK_FALSE(r.has_var("particle_count"));
  CHECK_FALSE(r.has_var("particle_x"));
}

TEST_CASE("NetcdfWriter writes maps alone, with the depth's own description", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "columns.nc";
  const Grid grid = small_grid();
  Layout layout = layout_of(grid, false);
  layout.depth_long_name = "water depth: particles standing in the cell";
  const Maps first = make_maps(grid.nx * grid.ny, 0.0);
  const Maps second = make_maps(grid.nx * grid.ny, 7.0);
  {
    NetcdfWriter w(file, layout, metadata());
    w.write(0.0, first.fields());
    w.write(0.5, second.fields());
    CHECK(w.records() == 2);
    w.finish();
  }
  Reader r(file);
  CHECK(r.dim("time") == 2);
  CHECK_FALSE(r.has_var("particle_count"));
  CHECK(r.text("depth", "long_name") == "water depth: particles standing in the cell");
  CHECK(r.all_doubles("time") == std::vector<double>{0.0, 0.5});
  const auto depth = r.floats("depth");
  REQUIRE(depth.size() == 2 * grid.nx * grid.ny);
  CHECK(depth[grid.nx * grid.ny + 5] == Approx(second.depth[5]));
  CHECK(depth[5] == Approx(first.depth[5]));
}

TEST_CASE("NetcdfWriter laid out with particles refuses maps without them", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "needs_particles.nc";
  const Grid grid = small_grid();
  NetcdfWriter w(file, layout_of(grid, true), metadata());
  CHECK_THROWS_AS(w.write(0.0, make_maps(grid.nx * grid.ny, 0.0).fields()), std::logic_error);
  CHECK(w.records() == 0);
  // The default depth description is the shallow-water maps': cell averages.
  w.write(0.0, make_particles(1, 0), make_maps(grid.nx * grid.ny, 0.0).fields());
  w.finish();
  CHECK_THAT(Reader(file).text("depth", "long_name"), Catch::Contains("cell average"));
}

TEST_CASE("NetcdfWriter destroyed without finish leaves only the partial file", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "crashed.nc";
  const Grid grid = small_grid();
  {
    NetcdfWriter w(file, layout_of(grid, true), metadata());
    w.write(0.0, make_particles(2, 0), make_maps(grid.nx * grid.ny, 0.0).fields());
  }
  CHECK_FALSE(fs::exists(file));
  REQUIRE(fs::exists(partial_of(file)));
  // What was written before the writer went away is still readable.
  Reader r(partial_of(file));
  CHECK(r.dim("time") == 1);
}

TEST_CASE("NetcdfWriter finish replaces an existing file", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "again.nc";
  std::ofstream(file) << "old result";
  const Grid grid = small_grid();
  NetcdfWriter w(file, layout_of(grid, false), metadata());
  CHECK(fs::exists(file));  // the old result stays until the new one is complete
  w.write(0.0, SweParticles{}, make_maps(grid.nx * grid.ny, 0.0).fields());
  w.finish();
  Reader r(file);
  CHECK(r.dim("time") == 1);
}

TEST_CASE("NetcdfWriter rejects a map of the wrong size", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "bad_size.nc";
  const Grid grid = small_grid();
  const std::size_t cells = grid.nx * grid.ny;
  NetcdfWriter w(file, layout_of(grid, true), metadata());
  const Maps good = make_maps(cells, 0.0);
  const std::vector<double> short_field(cells - 1, 0.0);
  const SweParticles p = make_particles(1, 0);
  CHECK_THROWS_AS(w.write(0.0, p, {short_field, good.surface, good.u, good.v}),
                  std::invalid_argument);
  CHECK_THROWS_AS(w.write(0.0, p, {good.depth, short_field, good.u, good.v}),
                  std::invalid_argument);
  CHECK_THROWS_AS(w.write(0.0, p, {good.depth, good.surface, short_field, good.v}),
                  std::invalid_argument);
  CHECK_THROWS_AS(w.write(0.0, p, {good.depth, good.surface, good.u, {}}), std::invalid_argument);
  CHECK(w.records() == 0);
}

TEST_CASE("NetcdfWriter reports a file it cannot create", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "no_such_folder" / "out.nc";
  try {
    NetcdfWriter w(file, layout_of(small_grid(), true), metadata());
    FAIL("expected std::runtime_error");
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    INFO(msg);
    CHECK(msg.find(file.string()) != std::string::npos);
    CHECK(msg.find("is not an existing folder") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(file.parent_path()));
}
