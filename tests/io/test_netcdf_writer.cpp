#include <netcdf.h>

#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "swemps/io/netcdf_writer.hpp"
#include "swemps/particles/swe_particles.hpp"

namespace fs = std::filesystem;
using swemps::io::Grid;
using swemps::io::NetcdfWriter;
using swemps::io::RunMetadata;
using swemps::particles::SweParticles;

namespace {

// A fresh folder per test case, removed afterwards, so parallel test runs never collide.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    dir_ = fs::temp_directory_path() /
           ("swemps-netcdf-test-" + std::to_string(stamp) + "-" + std::to_string(rd()));
    fs::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return dir_; }

 private:
  fs::path dir_;
};

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

std::vector<double> depth_field(std::size_t n, double offset) {
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = offset + 0.25 * static_cast<double>(i);
  return d;
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
  int ncid() const { return ncid_; }

 private:
  int ncid_ = -1;
};

bool on_path(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
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
  const auto d0 = depth_field(cells, 0.0);
  const auto d1 = depth_field(cells, 1.0);

  {
    NetcdfWriter w(file, grid, metadata(), true);
    CHECK(w.path() == file);
    w.write(0.0, p0, d0);
    w.write(2.5, p1, d1);
    CHECK(w.records() == 2);
    CHECK(fs::exists(partial_of(file)));
    CHECK_FALSE(fs::exists(file));
    w.finish();
    CHECK(fs::exists(file));
    CHECK_FALSE(fs::exists(partial_of(file)));
    CHECK_THROWS_AS(w.finish(), std::logic_error);
    CHECK_THROWS_AS(w.write(5.0, p0, d0), std::logic_error);
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
    double g = 0.0;
    nc_ok(nc_get_att_double(r.ncid(), NC_GLOBAL, "gravity_m_s2", &g));
    CHECK(g == 9.80665);
  }
  SECTION("dimensions and coordinates") {
    CHECK(r.dim("time") == 2);
    CHECK(r.dim("y") == 3);
    CHECK(r.dim("x") == 4);
    CHECK(r.dim("particle_sample") == 8);
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
  }
  SECTION("depth maps") {
    CHECK(r.text("depth", "units") == "m");
    CHECK(r.text("depth", "standard_name") == "flood_water_thickness");
    nc_type type = NC_NAT;
    nc_ok(nc_inq_vartype(r.ncid(), r.var("depth"), &type));
    CHECK(type == NC_FLOAT);
    std::vector<float> all(2 * cells);
    nc_ok(nc_get_var_float(r.ncid(), r.var("depth"), all.data()));
    for (std::size_t i = 0; i < cells; ++i) {
      CHECK(all[i] == static_cast<float>(d0[i]));
      CHECK(all[cells + i] == static_cast<float>(d1[i]));
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
  }
}

TEST_CASE("NetcdfWriter output opens in common command-line readers", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "tools.nc";
  const Grid grid = small_grid();
  {
    NetcdfWriter w(file, grid, metadata(), true);
    w.write(1.0, make_particles(2, 0), depth_field(grid.nx * grid.ny, 0.5));
    w.finish();
  }
  const std::string quiet = " >/dev/null 2>&1";
  if (on_path("ncdump")) {
    CHECK(std::system(("ncdump -h \"" + file.string() + "\"" + quiet).c_str()) == 0);
  } else {
    WARN("ncdump not found; header dump not checked");
  }
  if (on_path("gdalinfo")) {
    const std::string cmd = "gdalinfo 'NETCDF:\"" + file.string() + "\":depth'" + quiet;
    CHECK(std::system(cmd.c_str()) == 0);
  } else {
    WARN("gdalinfo not found; raster reading not checked");
  }
}

TEST_CASE("NetcdfWriter without particles defines no particle variables", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "grid_only.nc";
  const Grid grid = small_grid();
  {
    NetcdfWriter w(file, grid, metadata(), false);
    w.write(0.0, make_particles(2, 0), depth_field(grid.nx * grid.ny, 0.0));
    w.finish();
  }
  Reader r(file);
  CHECK(r.dim("time") == 1);
  CHECK_FALSE(r.has_dim("particle_sample"));
  CHECK_FALSE(r.has_var("particle_count"));
  CHECK_FALSE(r.has_var("particle_x"));
}

TEST_CASE("NetcdfWriter destroyed without finish leaves only the partial file", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "crashed.nc";
  const Grid grid = small_grid();
  {
    NetcdfWriter w(file, grid, metadata(), true);
    w.write(0.0, make_particles(2, 0), depth_field(grid.nx * grid.ny, 0.0));
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
  NetcdfWriter w(file, grid, metadata(), false);
  CHECK(fs::exists(file));  // the old result stays until the new one is complete
  w.write(0.0, SweParticles{}, depth_field(grid.nx * grid.ny, 0.0));
  w.finish();
  Reader r(file);
  CHECK(r.dim("time") == 1);
}

TEST_CASE("NetcdfWriter rejects a depth map of the wrong size", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "bad_size.nc";
  const Grid grid = small_grid();
  NetcdfWriter w(file, grid, metadata(), true);
  CHECK_THROWS_AS(w.write(0.0, make_particles(1, 0), depth_field(grid.nx * grid.ny - 1, 0.0)),
                  std::invalid_argument);
  CHECK(w.records() == 0);
}

TEST_CASE("NetcdfWriter reports a file it cannot create", "[io][netcdf]") {
  TempDir tmp;
  const fs::path file = tmp.path() / "no_such_folder" / "out.nc";
  try {
    NetcdfWriter w(file, small_grid(), metadata(), true);
    FAIL("expected std::runtime_error");
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    INFO(msg);
    CHECK(msg.find(file.string()) != std::string::npos);
    CHECK(msg.find("is not an existing folder") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(file.parent_path()));
}
