#pragma once
// Private to the io module: what the netCDF writer and the readers of its files share. The
// constants of the file layout, netCDF error checks, the CRS as CF attributes, and the two
// classes that define a new file's variables (Definer) and find them again in a file an
// earlier writer left (Resumer).

#include <netcdf.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "swemps/io/netcdf_writer.hpp"

namespace swemps::io::netcdf {

// Samples per chunk of the particle variables: large enough that compression works on
// whole blocks, small enough that a short run does not allocate a huge first chunk.
inline constexpr std::size_t kParticleChunk = 65536;
// Values per chunk of a map: one time slice of any grid a run is likely to use (2048 x
// 2048), split into bands of rows beyond that so no chunk nears HDF5's 4 GiB limit.
inline constexpr std::size_t kMapChunkValues = std::size_t{1} << 22;
// Values per chunk of a time series: a chunk of one per sample would make the file mostly
// chunk index.
inline constexpr std::size_t kSeriesChunkValues = 4096;
// Deflate level of maps and series: maps are written once per output time, so the size
// they save is worth more than the time level 4 costs over level 1.
inline constexpr int kDeflateLevel = 4;

// netCDF's default fill values: readers that ignore _FillValue still treat them as missing.
inline constexpr float kFillFloat = NC_FILL_FLOAT;
inline constexpr double kFillDouble = NC_FILL_DOUBLE;
inline constexpr unsigned char kFillClass = NC_FILL_UBYTE;  // 255

// The path in quotes, for messages.
std::string quoted(const std::filesystem::path& p);
// Every netCDF call goes through here so that a failure always reports what was being
// done, to which file, and netCDF's own explanation: throws std::runtime_error.
void check(int status, const std::string& purpose, const std::filesystem::path& file);
// Creates (or truncates) a netCDF-4 file and returns its id.
int create_netcdf4(const std::filesystem::path& file);
// NaN becomes the fill value.
std::vector<float> to_stored_floats(std::span<const double> values);
double to_stored(double v);
// Shortest text that reads back as the same double.
std::string exact_text(double v);

// One numeric attribute of a CF grid mapping (two values for standard_parallel).
struct CfParameter {
  std::string name;
  std::vector<double> values;
};

struct Crs {
  std::string wkt;                  // normalised, for crs_wkt and spatial_ref
  std::string name;                 // e.g. "WGS 84 / UTM zone 16N"
  std::string grid_mapping_name;    // CF name; empty where not derived
  std::vector<CfParameter> params;  // CF parameters of grid_mapping_name
};

// Parses and checks the grid's CRS. Throws std::invalid_argument for WKT that GDAL cannot
// read or a CRS whose x and y are not metres: the model's coordinates are metres, so any
// other CRS would misplace the grid.
Crs describe_crs(const std::string& wkt, const std::filesystem::path& file);

// GDAL's affine transform of the grid, "x_left dx 0 y_top 0 -dy", for the north-up image
// that GDAL presents (it flips rows stored with y ascending).
std::string geo_transform(const Grid& g);

// ---------------------------------------------------------------------------------------
// Layout

// Defines the file's variables; kept apart from the writer so that the class holds only
// what is needed while records are appended.
class Definer {
 public:
  Definer(int ncid, const std::filesystem::path& file, const Grid& grid)
      : ncid_(ncid), file_(file), grid_(grid) {}

  detail::NetcdfIds define(const Layout& layout, const RunMetadata& meta) const {
    put_globals(meta);
    detail::NetcdfIds ids;
    int time_dim = -1;
    ok(nc_def_dim(ncid_, "time", NC_UNLIMITED, &time_dim), "define dimension time");
    const GridIds grid = define_grid();
    ids.y_dim = grid.y_dim;
    ids.x_dim = grid.x_dim;

    ids.time = time_variable("time", time_dim, "simulated time of the maps and particles",
                             meta.time_units);
    const std::array map_dims{time_dim, ids.y_dim, ids.x_dim};
    // CF's name for the depth of water standing on land (the sea-floor names assume an
    // ocean).
    ids.depth =
        map_var("depth", map_dims, "m", "flood_water_thickness", layout.depth_long_name.c_str());
    // The datum is the terrain model's, hence no standard name that fixes one (geoid,
    // ellipsoid, mean sea level).
    ids.surface = map_var("surface_elevation", map_dims, "m", nullptr,
                          "water-surface elevation: bed elevation plus water depth");
    // CF's velocity names are for sea water and eastward/northward components; these are
    // along the grid axes of a flood on land, so they carry a long name only.
    ids.u = map_var("u", map_dims, "m s-1", nullptr, "depth-averaged velocity along x");
    ids.v = map_var("v", map_dims, "m s-1", nullptr, "depth-averaged velocity along y");
    if (layout.particles) define_particles(time_dim, ids);
    define_series(layout.gauges, meta.time_units, ids);
    define_provenance(layout, time_dim, ids);
    ok(nc_enddef(ncid_), "leave define mode");

    write_grid(grid);
    write_gauges(layout.gauges);
    write_sources(layout.sources);
    return ids;
  }

  // The grid alone: dimensions y and x, their coordinate variables and the CRS. A file of
  // maps without time (the products of an ensemble) defines this, its maps, and then writes
  // the axes with write_grid() once out of define mode.
  struct GridIds {
    int y_dim = -1, x_dim = -1, x_var = -1, y_var = -1;
  };
  GridIds define_grid() const {
    GridIds ids;
    ok(nc_def_dim(ncid_, "y", grid_.ny, &ids.y_dim), "define dimension y");
    ok(nc_def_dim(ncid_, "x", grid_.nx, &ids.x_dim), "define dimension x");
    ids.x_var = coordinate("x", ids.x_dim, "X");
    ids.y_var = coordinate("y", ids.y_dim, "Y");
    if (georeferenced()) define_crs(describe_crs(grid_.crs_wkt, file_));
    return ids;
  }
  void write_grid(const GridIds& ids) const {
    write_axis(ids.x_var, grid_.x0, grid_.dx, grid_.nx, "write variable x");
    write_axis(ids.y_var, grid_.y0, grid_.dy, grid_.ny, "write variable y");
  }

  // A variable written once is added when it is written (netCDF-4 lets variables be
  // defined after data), between these two calls.
  void redefine() const { ok(nc_redef(ncid_), "enter define mode"); }
  void end_define() const { ok(nc_enddef(ncid_), "leave define mode"); }

  // A static float map over (y, x).
  int static_map_var(const detail::NetcdfIds& ids, const char* name, const char* units,
                     const char* standard_name, const char* long_name) const {
    return map_var(name, std::array{ids.y_dim, ids.x_dim}, units, standard_name, long_name);
  }

  // A float map over (depth_threshold, y, x): one map per depth threshold.
  int threshold_map_var(const detail::NetcdfIds& ids, int threshold_dim, const char* name,
                        const char* units, const char* long_name) const {
    return map_var(name, std::array{threshold_dim, ids.y_dim, ids.x_dim}, units, nullptr,
                   long_name);
  }

  // A map of classes over (y, x): unsigned bytes, kFillClass where the cell had no data.
  int class_map_var(const detail::NetcdfIds& ids, const char* name, const char* long_name) const {
    const std::array dims{ids.y_dim, ids.x_dim};
    const int id = def_var(name, NC_UBYTE, dims);
    const std::size_t rows =
        std::clamp<std::size_t>(kMapChunkValues / grid_.nx, std::size_t{1}, grid_.ny);
    compress(id, name, std::array{rows, grid_.nx}, kDeflateLevel);
    ok(nc_put_att_uchar(ncid_, id, "_FillValue", NC_UBYTE, 1, &kFillClass),
       std::string("write attribute _FillValue of ") + name);
    text(id, "long_name", long_name);
    if (georeferenced()) text(id, "grid_mapping", "crs");
    return id;
  }
  void bytes(int varid, const char* name, std::span<const unsigned char> values) const {
    ok(nc_put_att_uchar(ncid_, varid, name, NC_UBYTE, values.size(), values.data()),
       std::string("write attribute ") + name);
  }

  // A dimension of fixed length, or the one of that name a resumed file already has, which
  // must be as long.
  int dimension(const char* name, std::size_t length) const {
    int id = -1;
    if (nc_inq_dimid(ncid_, name, &id) == NC_NOERR) {
      std::size_t found = 0;
      ok(nc_inq_dimlen(ncid_, id, &found), std::string("read the length of dimension ") + name);
      if (found != length) {
        throw std::runtime_error("netCDF: the file " + quoted(file_) + " has " +
                                 std::to_string(found) + " along " + name + ", this run " +
                                 std::to_string(length));
      }
      return id;
    }
    ok(nc_def_dim(ncid_, name, length, &id), std::string("define dimension ") + name);
    return id;
  }
  int variable(const char* name, nc_type type, int dim) const {
    return def_var(name, type, std::array{dim});
  }

  void text(int varid, const char* name, const std::string& value) const {
    ok(nc_put_att_text(ncid_, varid, name, value.size(), value.c_str()),
       std::string("write attribute ") + name);
  }
  void texts(int varid, std::initializer_list<std::pair<const char*, const char*>> atts) const {
    for (const auto& [name, value] : atts) text(varid, name, value);
  }
  void number(int varid, const char* name, std::span<const double> values) const {
    ok(nc_put_att_double(ncid_, varid, name, NC_DOUBLE, values.size(), values.data()),
       std::string("write attribute ") + name);
  }
  void number(int varid, const char* name, double value) const {
    number(varid, name, std::span<const double>(&value, 1));
  }
  // A 32-bit integer: CF-1.8 has no 64-bit attribute type.
  void integer(int varid, const char* name, std::size_t value) const {
    const int stored = static_cast<int>(std::min<std::size_t>(value, INT_MAX));
    ok(nc_put_att_int(ncid_, varid, name, NC_INT, 1, &stored),
       std::string("write attribute ") + name);
  }

 private:
  void ok(int status, const std::string& purpose) const { check(status, purpose, file_); }
  bool georeferenced() const { return !grid_.crs_wkt.empty(); }

  template <std::size_t N>
  int def_var(const char* name, nc_type type, const std::array<int, N>& dims) const {
    int varid = -1;
    ok(nc_def_var(ncid_, name, type, static_cast<int>(N), dims.data(), &varid),
       std::string("define variable ") + name);
    return varid;
  }

  void compress(int varid, const char* name, std::span<const std::size_t> chunk, int level) const {
    ok(nc_def_var_chunking(ncid_, varid, NC_CHUNKED, chunk.data()),
       std::string("set chunking of ") + name);
    // Shuffle groups the bytes of like significance, which deflate then compresses far
    // better for floating-point fields.
    ok(nc_def_var_deflate(ncid_, varid, 1, 1, level), std::string("set compression of ") + name);
  }

  void put_globals(const RunMetadata& meta) const {
    // No global featureType: CF applies it to every variable of the file, and the file is
    // first of all a set of grids; the gauge series carry their own DSG attributes.
    texts(NC_GLOBAL, {{"Conventions", "CF-1.8"}, {"references", "swe-mps shallow-water MPS"}});
    text(NC_GLOBAL, "title", meta.title);
    text(NC_GLOBAL, "source", meta.scenario_file);
    text(NC_GLOBAL, "history", meta.history);
    number(NC_GLOBAL, "gravity_m_s2", meta.gravity_m_s2);
    put_provenance(meta);
  }

 public:
  // Where the file came from: the program, the scene as read with its defaults filled in, the
  // command line and when the run started; rewritten by a run that goes on with the file.
  void put_provenance(const RunMetadata& meta) const {
    const std::pair<const char*, const std::string*> attributes[] = {
        {"program", &meta.program},
        {"scenario", &meta.scene_json},
        {"command_line", &meta.command_line},
        {"run_started", &meta.run_started},
        {"time_coverage_start", &meta.start_time}};
    for (const auto& [name, value] : attributes) {
      if (!value->empty()) text(NC_GLOBAL, name, *value);
    }
  }

 private:
  int coordinate(const char* name, int dim, const char* axis) const {
    const int id = def_var(name, NC_DOUBLE, std::array{dim});
    const std::string n(name);
    text(id, "units", "m");
    text(id, "standard_name", "projection_" + n + "_coordinate");
    text(id, "long_name", n + " coordinate of cell centre");
    text(id, "axis", axis);
    return id;
  }

  void define_crs(const Crs& crs) const {
    const int id = def_var("crs", NC_INT, std::array<int, 0>{});
    if (!crs.grid_mapping_name.empty()) {
      text(id, "grid_mapping_name", crs.grid_mapping_name);
      for (const CfParameter& p : crs.params) number(id, p.name.c_str(), p.values);
    }
    if (!crs.name.empty()) text(id, "projected_crs_name", crs.name);
    // crs_wkt is CF's attribute; spatial_ref and GeoTransform are what GDAL reads first.
    text(id, "crs_wkt", crs.wkt);
    text(id, "spatial_ref", crs.wkt);
    text(id, "GeoTransform", geo_transform(grid_));
    text(id, "long_name", "coordinate reference system of x and y");
  }

  // Without the scene's start time the epoch is nominal (RunMetadata::time_units): the
  // model then has no calendar date, and "seconds since" lets readers treat the axis as time.
  int time_variable(const char* name, int dim, const char* long_name,
                    const std::string& units) const {
    const int id = def_var(name, NC_DOUBLE, std::array{dim});
    texts(id, {{"standard_name", "time"},
               {"long_name", long_name},
               {"axis", "T"},
               {"calendar", "standard"}});
    text(id, "units", units);
    return id;
  }

  // A float map over (time, y, x) or (y, x): single precision is ample for a map and
  // halves the file; NaN becomes the fill value.
  template <std::size_t N>
  int map_var(const char* name, const std::array<int, N>& dims, const char* units,
              const char* standard_name, const char* long_name) const {
    const int id = def_var(name, NC_FLOAT, dims);
    const std::size_t rows =
        std::clamp<std::size_t>(kMapChunkValues / grid_.nx, std::size_t{1}, grid_.ny);
    std::array<std::size_t, N> chunk{};
    chunk.fill(1);
    chunk[N - 2] = rows;
    chunk[N - 1] = grid_.nx;
    compress(id, name, chunk, kDeflateLevel);
    ok(nc_put_att_float(ncid_, id, "_FillValue", NC_FLOAT, 1, &kFillFloat),
       std::string("write attribute _FillValue of ") + name);
    text(id, "units", units);
    if (standard_name) text(id, "standard_name", standard_name);
    text(id, "long_name", long_name);
    if (georeferenced()) text(id, "grid_mapping", "crs");
    return id;
  }

  int particle_var(int sample_dim, const char* name, const char* units,
                   const char* long_name) const {
    const int id = def_var(name, NC_DOUBLE, std::array{sample_dim});
    // Light compression: particle output is large and written often, so speed matters more
    // than the last few percent of size.
    compress(id, name, std::array{kParticleChunk}, 1);
    texts(id, {{"units", units}, {"long_name", long_name}});
    return id;
  }

  void define_particles(int time_dim, detail::NetcdfIds& ids) const {
    int sample_dim = -1;
    ok(nc_def_dim(ncid_, "particle_sample", NC_UNLIMITED, &sample_dim),
       "define dimension particle_sample");
    // CF contiguous ragged array: record r owns the samples after those of records < r.
    ids.count = def_var("particle_count", NC_INT, std::array{time_dim});
    texts(ids.count, {{"long_name", "number of particles at this time"},
                      {"sample_dimension", "particle_sample"}});
    ids.px = particle_var(sample_dim, "particle_x", "m", "particle x position");
    ids.py = particle_var(sample_dim, "particle_y", "m", "particle y position");
    ids.pu = particle_var(sample_dim, "particle_u", "m s-1", "particle depth-averaged x velocity");
    ids.pv = particle_var(sample_dim, "particle_v", "m s-1", "particle depth-averaged y velocity");
    ids.ph = particle_var(sample_dim, "particle_depth", "m", "particle water depth");
    ids.pvol = particle_var(sample_dim, "particle_volume", "m3", "particle volume");
    ids.parea = particle_var(sample_dim, "particle_area", "m2", "particle area");
  }

  // A double series over (series_time) or (series_time, gauge); NaN becomes the fill value.
  template <std::size_t N>
  int series_var(const char* name, const std::array<int, N>& dims, std::size_t width,
                 const char* units, const char* long_name) const {
    const int id = def_var(name, NC_DOUBLE, dims);
    std::array<std::size_t, N> chunk{};
    chunk[0] = std::max<std::size_t>(1, kSeriesChunkValues / width);
    if constexpr (N == 2) chunk[1] = width;
    compress(id, name, chunk, kDeflateLevel);
    ok(nc_put_att_double(ncid_, id, "_FillValue", NC_DOUBLE, 1, &kFillDouble),
       std::string("write attribute _FillValue of ") + name);
    texts(id, {{"units", units}, {"long_name", long_name}});
    return id;
  }

  void define_series(const std::vector<Gauge>& gauges, const std::string& time_units,
                     detail::NetcdfIds& ids) const {
    int series_dim = -1;
    ok(nc_def_dim(ncid_, "series_time", NC_UNLIMITED, &series_dim), "define dimension series_time");
    ids.series_time =
        time_variable("series_time", series_dim,
                      "simulated time of the gauge and volume-balance samples", time_units);
    const std::array balance_dims{series_dim};
    ids.in_domain =
        series_var("volume_in_domain", balance_dims, 1, "m3", "volume of water in the domain");
    ids.inflow =
        series_var("volume_inflow", balance_dims, 1, "m3", "cumulative volume that flowed in");
    ids.rain = series_var("volume_rain", balance_dims, 1, "m3",
                          "cumulative volume of rain that reached the water, after losses");
    ids.outflow = series_var("volume_outflow", balance_dims, 1, "m3",
                             "cumulative volume that flowed out or was removed");
    ids.error = series_var("volume_error", balance_dims, 1, "1",
                           "relative volume balance error: (in domain - (initial + inflow + "
                           "rain - outflow)) / reference volume");
    if (gauges.empty()) return;

    int gauge_dim = -1;
    ok(nc_def_dim(ncid_, "gauge", gauges.size(), &gauge_dim), "define dimension gauge");
    // CF discrete sampling geometry, orthogonal multidimensional time series: every gauge
    // shares series_time, and gauge_name identifies the series.
    const int name = def_var("gauge_name", NC_STRING, std::array{gauge_dim});
    texts(name, {{"cf_role", "timeseries_id"}, {"long_name", "gauge name"}});
    const int gx = def_var("gauge_x", NC_DOUBLE, std::array{gauge_dim});
    const int gy = def_var("gauge_y", NC_DOUBLE, std::array{gauge_dim});
    texts(gx, {{"units", "m"},
               {"standard_name", "projection_x_coordinate"},
               {"long_name", "gauge x position"}});
    texts(gy, {{"units", "m"},
               {"standard_name", "projection_y_coordinate"},
               {"long_name", "gauge y position"}});

    const std::array dims{series_dim, gauge_dim};
    const std::size_t n = gauges.size();
    ids.gauge_depth = series_var("gauge_depth", dims, n, "m", "water depth at the gauge");
    ids.gauge_surface = series_var("gauge_surface_elevation", dims, n, "m",
                                   "water-surface elevation (bed plus depth) at the gauge; fill "
                                   "value where the gauge is not wet");
    ids.gauge_u =
        series_var("gauge_u", dims, n, "m s-1", "depth-averaged velocity along x at the gauge");
    ids.gauge_v =
        series_var("gauge_v", dims, n, "m s-1", "depth-averaged velocity along y at the gauge");
    for (const int id : {ids.gauge_depth, ids.gauge_surface, ids.gauge_u, ids.gauge_v}) {
      text(id, "coordinates", "gauge_x gauge_y gauge_name");
      if (georeferenced()) text(id, "grid_mapping", "crs");
    }
  }

  // Where the water came from (docs/provenance.md): the sources along dimension `source`, the
  // maps of each one's water and of the water's mean age, each source's volume balance and its
  // share at the gauges.
  void define_provenance(const Layout& layout, int time_dim, detail::NetcdfIds& ids) const {
    if (layout.ages) {
      ids.mean_age = map_var("mean_age", std::array{time_dim, ids.y_dim, ids.x_dim}, "s", nullptr,
                             "volume-weighted mean age of the cell's water: the time since it "
                             "entered the domain (the starting water at t = 0)");
    }
    if (layout.sources.empty()) return;
    int source_dim = -1;
    ok(nc_def_dim(ncid_, "source", layout.sources.size(), &source_dim), "define dimension source");
    // A numeric coordinate (CF's coordinate variables are numbers) that GDAL shows in each
    // band's metadata as NETCDF_DIM_source; source_name labels it.
    const int index = def_var("source", NC_INT, std::array{source_dim});
    texts(index, {{"long_name", "index of the source of the water in source_name"},
                  {"units", "1"}});
    const int name = def_var("source_name", NC_STRING, std::array{source_dim});
    text(name, "long_name",
         "name of the source of the water (a water body, inflow, sea boundary "
         "or rain of the scene)");
    const std::array dims{time_dim, source_dim, ids.y_dim, ids.x_dim};
    ids.source_depth = map_var("source_depth", dims, "m", nullptr,
                               "depth of the water that came from each source");
    ids.source_share = map_var("source_share", dims, "1", nullptr,
                               "share of the cell's water that came from each source; fill "
                               "value where the cell is not wet");
    for (const int id : {ids.source_depth, ids.source_share}) {
      text(id, "coordinates", "source_name");
    }
    int series_dim = -1;
    ok(nc_inq_dimid(ncid_, "series_time", &series_dim), "find dimension series_time");
    const std::size_t n = layout.sources.size();
    const std::array balance_dims{series_dim, source_dim};
    ids.source_in_domain = series_var("source_volume_in_domain", balance_dims, n, "m3",
                                      "volume of each source's water in the domain");
    ids.source_inflow = series_var("source_volume_inflow", balance_dims, n, "m3",
                                   "cumulative volume of each source's water that entered after "
                                   "the start (inflow, sea boundary, rain)");
    ids.source_outflow = series_var("source_volume_outflow", balance_dims, n, "m3",
                                    "cumulative volume of each source's water that flowed out or "
                                    "was removed");
    ids.source_error = series_var("source_volume_error", balance_dims, n, "1",
                                  "relative volume balance error of each source's water: (in "
                                  "domain - (initial + inflow - outflow)) / (initial + inflow)");
    for (const int id :
         {ids.source_in_domain, ids.source_inflow, ids.source_outflow, ids.source_error}) {
      text(id, "coordinates", "source_name");
    }
    if (layout.gauges.empty()) return;
    int gauge_dim = -1;
    ok(nc_inq_dimid(ncid_, "gauge", &gauge_dim), "find dimension gauge");
    const char* share_name = "gauge_source_share";
    ids.gauge_source_share =
        def_var(share_name, NC_DOUBLE, std::array{series_dim, gauge_dim, source_dim});
    const std::size_t width = layout.gauges.size() * n;
    compress(
        ids.gauge_source_share, share_name,
        std::array{std::max<std::size_t>(1, kSeriesChunkValues / width), layout.gauges.size(), n},
        kDeflateLevel);
    ok(nc_put_att_double(ncid_, ids.gauge_source_share, "_FillValue", NC_DOUBLE, 1, &kFillDouble),
       "write attribute _FillValue of gauge_source_share");
    texts(ids.gauge_source_share,
          {{"units", "1"},
           {"long_name",
            "share of each source in the water at the gauge; fill value where the "
            "gauge is not wet"},
           {"coordinates", "gauge_x gauge_y gauge_name source_name"}});
  }

  void write_sources(const std::vector<std::string>& sources) const {
    if (sources.empty()) return;
    std::vector<const char*> names;
    std::vector<int> indices;
    for (const std::string& s : sources) {
      names.push_back(s.c_str());
      indices.push_back(static_cast<int>(indices.size()));
    }
    int id = -1;
    ok(nc_inq_varid(ncid_, "source_name", &id), "find variable source_name");
    ok(nc_put_var_string(ncid_, id, names.data()), "write variable source_name");
    ok(nc_inq_varid(ncid_, "source", &id), "find variable source");
    ok(nc_put_var_int(ncid_, id, indices.data()), "write variable source");
  }

  void write_axis(int varid, double origin, double step, std::size_t n, const char* purpose) const {
    std::vector<double> values(n);
    for (std::size_t i = 0; i < n; ++i) values[i] = origin + static_cast<double>(i) * step;
    ok(nc_put_var_double(ncid_, varid, values.data()), purpose);
  }

  void write_gauges(const std::vector<Gauge>& gauges) const {
    if (gauges.empty()) return;
    std::vector<const char*> names;
    std::vector<double> xs, ys;
    for (const Gauge& g : gauges) {
      names.push_back(g.name.c_str());
      xs.push_back(g.x);
      ys.push_back(g.y);
    }
    const auto var = [this](const char* name) {
      int id = -1;
      ok(nc_inq_varid(ncid_, name, &id), std::string("find variable ") + name);
      return id;
    };
    ok(nc_put_var_string(ncid_, var("gauge_name"), names.data()), "write variable gauge_name");
    ok(nc_put_var_double(ncid_, var("gauge_x"), xs.data()), "write variable gauge_x");
    ok(nc_put_var_double(ncid_, var("gauge_y"), ys.data()), "write variable gauge_y");
  }

  int ncid_;
  const std::filesystem::path& file_;
  const Grid& grid_;
};

// Finds the dimensions and variables of a file an earlier writer defined, and checks that they
// have the layout this writer would have given them.
class Resumer {
 public:
  Resumer(int ncid, const std::filesystem::path& file) : ncid_(ncid), file_(file) {}

  detail::NetcdfIds find(const Layout& layout, const WriterPosition& position) const {
    detail::NetcdfIds ids;
    ids.y_dim = dimension("y");
    ids.x_dim = dimension("x");
    require_length("y", ids.y_dim, layout.grid.ny);
    require_length("x", ids.x_dim, layout.grid.nx);
    require_axis("x", layout.grid.x0, layout.grid.dx, layout.grid.nx);
    require_axis("y", layout.grid.y0, layout.grid.dy, layout.grid.ny);
    ids.time = variable("time");
    ids.depth = variable("depth");
    ids.surface = variable("surface_elevation");
    ids.u = variable("u");
    ids.v = variable("v");
    const bool has_particles = optional_variable("particle_count") >= 0;
    if (has_particles != layout.particles) {
      mismatch(layout.particles ? "has no particles, which this run writes"
                                : "has particles, which this run does not write");
    }
    if (layout.particles) {
      ids.count = variable("particle_count");
      ids.px = variable("particle_x");
      ids.py = variable("particle_y");
      ids.pu = variable("particle_u");
      ids.pv = variable("particle_v");
      ids.ph = variable("particle_depth");
      ids.pvol = variable("particle_volume");
      ids.parea = variable("particle_area");
    }
    ids.series_time = variable("series_time");
    ids.in_domain = variable("volume_in_domain");
    ids.inflow = variable("volume_inflow");
    ids.rain = variable("volume_rain");
    ids.outflow = variable("volume_outflow");
    ids.error = variable("volume_error");
    int gauge_dim = -1;
    std::size_t gauges = 0;
    if (nc_inq_dimid(ncid_, "gauge", &gauge_dim) == NC_NOERR) {
      ok(nc_inq_dimlen(ncid_, gauge_dim, &gauges), "read the length of dimension gauge");
    }
    if (gauges != layout.gauges.size()) {
      mismatch("has " + std::to_string(gauges) + " gauges, this run " +
               std::to_string(layout.gauges.size()));
    }
    if (gauges > 0) {
      ids.gauge_depth = variable("gauge_depth");
      ids.gauge_surface = variable("gauge_surface_elevation");
      ids.gauge_u = variable("gauge_u");
      ids.gauge_v = variable("gauge_v");
    }
    find_provenance(layout, ids);

    const std::size_t records = length_of(ids.time), series = length_of(ids.series_time);
    if (records < position.records || series < position.series_records) {
      mismatch("holds " + std::to_string(records) + " map times and " + std::to_string(series) +
               " series times, fewer than the " + std::to_string(position.records) + " and " +
               std::to_string(position.series_records) + " written before the checkpoint");
    }
    if (layout.particles && position.records > 0) {
      std::vector<int> counts(position.records);
      const std::size_t start = 0, count = position.records;
      ok(nc_get_vara_int(ncid_, ids.count, &start, &count, counts.data()),
         "read variable particle_count");
      std::size_t samples = 0;
      for (const int c : counts) samples += static_cast<std::size_t>(std::max(c, 0));
      if (samples != position.particle_samples) {
        mismatch("holds " + std::to_string(samples) + " particle samples in its first " +
                 std::to_string(position.records) + " map times, not the " +
                 std::to_string(position.particle_samples) + " written before the checkpoint");
      }
    }
    return ids;
  }

  bool has_variable(const char* name) const { return optional_variable(name) >= 0; }

  void find_provenance(const Layout& layout, detail::NetcdfIds& ids) const {
    if (has_variable("mean_age") != layout.ages) {
      mismatch(layout.ages ? "has no mean_age, which this run writes"
                           : "has mean_age, which this run does not write");
    }
    if (layout.ages) ids.mean_age = variable("mean_age");
    int source_dim = -1;
    std::size_t sources = 0;
    if (nc_inq_dimid(ncid_, "source", &source_dim) == NC_NOERR) {
      ok(nc_inq_dimlen(ncid_, source_dim, &sources), "read the length of dimension source");
    }
    if (sources != layout.sources.size()) {
      mismatch("has " + std::to_string(sources) + " sources of water, this run " +
               std::to_string(layout.sources.size()));
    }
    if (sources == 0) return;
    ids.source_depth = variable("source_depth");
    ids.source_share = variable("source_share");
    ids.source_in_domain = variable("source_volume_in_domain");
    ids.source_inflow = variable("source_volume_inflow");
    ids.source_outflow = variable("source_volume_outflow");
    ids.source_error = variable("source_volume_error");
    if (!layout.gauges.empty()) ids.gauge_source_share = variable("gauge_source_share");
  }

  int optional_variable(const char* name) const {
    int id = -1;
    return nc_inq_varid(ncid_, name, &id) == NC_NOERR ? id : -1;
  }

  std::string text_attribute(const char* name) const {
    std::size_t length = 0;
    if (nc_inq_attlen(ncid_, NC_GLOBAL, name, &length) != NC_NOERR) return {};
    std::string value(length, '\0');
    ok(nc_get_att_text(ncid_, NC_GLOBAL, name, value.data()),
       std::string("read attribute ") + name);
    return value;
  }

 private:
  void ok(int status, const std::string& purpose) const { check(status, purpose, file_); }

  [[noreturn]] void mismatch(const std::string& what) const {
    throw std::runtime_error("netCDF: the file " + quoted(file_) +
                             " does not match the run that is to continue it: it " + what);
  }

  int dimension(const char* name) const {
    int id = -1;
    if (nc_inq_dimid(ncid_, name, &id) != NC_NOERR) {
      mismatch(std::string("has no dimension ") + name);
    }
    return id;
  }

  int variable(const char* name) const {
    const int id = optional_variable(name);
    if (id < 0) mismatch(std::string("has no variable ") + name);
    return id;
  }

  std::size_t length_of(int varid) const {
    int dim = -1;
    ok(nc_inq_vardimid(ncid_, varid, &dim), "read the dimensions of a time variable");
    std::size_t length = 0;
    ok(nc_inq_dimlen(ncid_, dim, &length), "read the length of a time dimension");
    return length;
  }

  void require_length(const char* name, int dim, std::size_t expected) const {
    std::size_t length = 0;
    ok(nc_inq_dimlen(ncid_, dim, &length), std::string("read the length of dimension ") + name);
    if (length != expected) {
      mismatch(std::string("has ") + std::to_string(length) + " cells along " + name +
               ", this run's grid " + std::to_string(expected));
    }
  }

  // The axis as the writer computed it, compared exactly: the same grid gives the same values.
  void require_axis(const char* name, double origin, double step, std::size_t n) const {
    std::vector<double> values(n);
    ok(nc_get_var_double(ncid_, variable(name), values.data()),
       std::string("read variable ") + name);
    for (std::size_t i = 0; i < n; ++i) {
      if (values[i] != origin + static_cast<double>(i) * step) {
        mismatch(std::string("has other cell centres along ") + name + " than this run's grid");
      }
    }
  }

  int ncid_;
  const std::filesystem::path& file_;
};

}  // namespace swemps::io::netcdf
