#include "swemps/io/netcdf_writer.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "swemps/io/gdal_messages.hpp"

namespace swemps::io {

namespace {

// Samples per chunk of the particle variables: large enough that compression works on
// whole blocks, small enough that a short run does not allocate a huge first chunk.
constexpr std::size_t kParticleChunk = 65536;
// Values per chunk of a map: one time slice of any grid a run is likely to use (2048 x
// 2048), split into bands of rows beyond that so no chunk nears HDF5's 4 GiB limit.
constexpr std::size_t kMapChunkValues = std::size_t{1} << 22;
// Values per chunk of a time series: a chunk of one per sample would make the file mostly
// chunk index.
constexpr std::size_t kSeriesChunkValues = 4096;
// Deflate level of maps and series: maps are written once per output time, so the size
// they save is worth more than the time level 4 costs over level 1.
constexpr int kDeflateLevel = 4;

// netCDF's default fill values: readers that ignore _FillValue still treat them as missing.
constexpr float kFillFloat = NC_FILL_FLOAT;
constexpr double kFillDouble = NC_FILL_DOUBLE;

constexpr const char* kTimeUnits = "seconds since 1970-01-01 00:00:00";

std::string quoted(const std::filesystem::path& p) {
  // Appended piecewise: `"'" + string` trips a false -Wrestrict warning in GCC 12.
  std::string text(1, '\'');
  text += p.string();
  text += '\'';
  return text;
}

// Every netCDF call goes through here so that a failure always reports what was being
// done, to which file, and netCDF's own explanation.
void check(int status, const std::string& purpose, const std::filesystem::path& file) {
  if (status != NC_NOERR) {
    throw std::runtime_error("netCDF: cannot " + purpose + " (file " + quoted(file) +
                             "): " + nc_strerror(status));
  }
}

// Creates (or truncates) a netCDF-4 file and returns its id.
int create_netcdf4(const std::filesystem::path& file) {
  int ncid = -1;
  const int status = nc_create(file.c_str(), NC_NETCDF4 | NC_CLOBBER, &ncid);
  if (status == NC_NOERR) return ncid;
  std::string message =
      std::string("netCDF: cannot create the file ") + quoted(file) + ": " + nc_strerror(status);
  // A missing folder is reported as a permission problem; say what is really wrong.
  const std::filesystem::path folder = file.parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec)) {
    message += " (" + quoted(folder) + " is not an existing folder)";
  }
  throw std::runtime_error(message);
}

std::vector<float> to_stored_floats(std::span<const double> values) {
  std::vector<float> out(values.size());
  std::transform(values.begin(), values.end(), out.begin(),
                 [](double v) { return std::isnan(v) ? kFillFloat : static_cast<float>(v); });
  return out;
}

double to_stored(double v) { return std::isnan(v) ? kFillDouble : v; }

// Shortest text that reads back as the same double.
std::string exact_text(double v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), end);
}

// ---------------------------------------------------------------------------------------
// Coordinate reference system

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

// GDAL 3.6 has no export of a CRS to CF attributes (that came with 3.9), so the common
// projections of flood studies are translated here from their WKT1 parameters, which GDAL
// normalises to degrees and metres. Readers that rely on the CF attributes alone (Panoply)
// then place the grid; any other projection keeps only the WKT, which GDAL, QGIS and
// xarray-based tools read.
std::vector<CfParameter> cf_projection_parameters(const OGRSpatialReference& srs,
                                                  std::string& grid_mapping_name) {
  const char* projection = srs.GetAttrValue("PROJECTION");
  const std::string p = projection ? projection : "";
  const auto param = [&](const char* cf_name, const char* gdal_name) {
    return CfParameter{cf_name, {srs.GetNormProjParm(gdal_name, 0.0)}};
  };
  const auto parallels = [&] {
    return CfParameter{"standard_parallel",
                       {srs.GetNormProjParm(SRS_PP_STANDARD_PARALLEL_1, 0.0),
                        srs.GetNormProjParm(SRS_PP_STANDARD_PARALLEL_2, 0.0)}};
  };
  const CfParameter false_easting = param("false_easting", SRS_PP_FALSE_EASTING);
  const CfParameter false_northing = param("false_northing", SRS_PP_FALSE_NORTHING);

  if (p == SRS_PT_TRANSVERSE_MERCATOR) {  // UTM and most national grids
    grid_mapping_name = "transverse_mercator";
    return {param("scale_factor_at_central_meridian", SRS_PP_SCALE_FACTOR),
            param("longitude_of_central_meridian", SRS_PP_CENTRAL_MERIDIAN),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_ORIGIN), false_easting,
            false_northing};
  }
  if (p == SRS_PT_LAMBERT_CONFORMAL_CONIC_2SP) {
    grid_mapping_name = "lambert_conformal_conic";
    return {parallels(), param("longitude_of_central_meridian", SRS_PP_CENTRAL_MERIDIAN),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_ORIGIN), false_easting,
            false_northing};
  }
  if (p == SRS_PT_ALBERS_CONIC_EQUAL_AREA) {
    grid_mapping_name = "albers_conical_equal_area";
    return {parallels(), param("longitude_of_central_meridian", SRS_PP_LONGITUDE_OF_CENTER),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_CENTER), false_easting,
            false_northing};
  }
  if (p == SRS_PT_LAMBERT_AZIMUTHAL_EQUAL_AREA) {
    grid_mapping_name = "lambert_azimuthal_equal_area";
    return {param("longitude_of_projection_origin", SRS_PP_LONGITUDE_OF_CENTER),
            param("latitude_of_projection_origin", SRS_PP_LATITUDE_OF_CENTER), false_easting,
            false_northing};
  }
  if (p == SRS_PT_MERCATOR_1SP) {
    grid_mapping_name = "mercator";
    return {param("longitude_of_projection_origin", SRS_PP_CENTRAL_MERIDIAN),
            param("scale_factor_at_projection_origin", SRS_PP_SCALE_FACTOR), false_easting,
            false_northing};
  }
  grid_mapping_name.clear();
  return {};
}

// Parses and checks the grid's CRS. Throws std::invalid_argument for WKT that GDAL cannot
// read or a CRS whose x and y are not metres: the model's coordinates are metres, so any
// other CRS would misplace the grid.
Crs describe_crs(const std::string& wkt, const std::filesystem::path& file) {
  const std::string where = "NetcdfWriter: CRS of the grid for " + quoted(file);
  OGRSpatialReference srs;
  {
    // GDAL's complaint goes into the exception instead of onto stderr.
    const QuietGdalErrors quiet;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) {
      throw std::invalid_argument(where +
                                  " is not WKT that GDAL can read: " + CPLGetLastErrorMsg());
    }
  }
  if (!srs.IsProjected()) {
    throw std::invalid_argument(where + " is not a projected CRS (x and y must be metres)");
  }
  const char* unit_name = nullptr;
  const double unit_m = srs.GetLinearUnits(&unit_name);
  if (std::abs(unit_m - 1.0) > 1e-12) {
    throw std::invalid_argument(where + " has unit '" + (unit_name ? unit_name : "?") +
                                "', not metres");
  }

  Crs crs;
  // WKT1 is what older GDAL and QGIS versions read from spatial_ref; a CRS that WKT1
  // cannot express is written as WKT2 instead.
  char* text = nullptr;
  OGRErr status = srs.exportToWkt(&text);
  if (status != OGRERR_NONE) {
    CPLFree(text);
    text = nullptr;
    const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
    status = srs.exportToWkt(&text, options);
  }
  if (status != OGRERR_NONE || text == nullptr) {
    CPLFree(text);
    throw std::invalid_argument(where + " cannot be written as WKT");
  }
  crs.wkt = text;
  CPLFree(text);
  crs.name = srs.GetName() ? srs.GetName() : "";
  crs.params = cf_projection_parameters(srs, crs.grid_mapping_name);
  if (!crs.grid_mapping_name.empty()) {
    OGRErr err = OGRERR_NONE;
    const double semi_major = srs.GetSemiMajor(&err);
    const double inverse_flattening = srs.GetInvFlattening(&err);
    crs.params.push_back({"semi_major_axis", {semi_major}});
    crs.params.push_back({"inverse_flattening", {inverse_flattening}});
    crs.params.push_back({"longitude_of_prime_meridian", {srs.GetPrimeMeridian()}});
  }
  return crs;
}

// GDAL's affine transform of the grid, "x_left dx 0 y_top 0 -dy", for the north-up image
// that GDAL presents (it flips rows stored with y ascending).
std::string geo_transform(const Grid& g) {
  const double x_left = g.x0 - 0.5 * g.dx;
  const double y_top = g.y0 + (static_cast<double>(g.ny) - 0.5) * g.dy;
  return exact_text(x_left) + " " + exact_text(g.dx) + " 0 " + exact_text(y_top) + " 0 " +
         exact_text(-g.dy);
}

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
    ok(nc_def_dim(ncid_, "y", grid_.ny, &ids.y_dim), "define dimension y");
    ok(nc_def_dim(ncid_, "x", grid_.nx, &ids.x_dim), "define dimension x");

    const int x_var = coordinate("x", ids.x_dim, "X");
    const int y_var = coordinate("y", ids.y_dim, "Y");
    if (georeferenced()) define_crs(describe_crs(grid_.crs_wkt, file_));

    ids.time = time_variable("time", time_dim, "simulated time of the maps and particles");
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
    define_series(layout.gauges, ids);
    ok(nc_enddef(ncid_), "leave define mode");

    write_axis(x_var, grid_.x0, grid_.dx, grid_.nx, "write variable x");
    write_axis(y_var, grid_.y0, grid_.dy, grid_.ny, "write variable y");
    write_gauges(layout.gauges);
    return ids;
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
  }

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

  int time_variable(const char* name, int dim, const char* long_name) const {
    const int id = def_var(name, NC_DOUBLE, std::array{dim});
    // The epoch is nominal: the model has no calendar date, and "seconds since" lets
    // readers treat the axis as time.
    texts(id, {{"units", kTimeUnits},
               {"standard_name", "time"},
               {"long_name", long_name},
               {"axis", "T"},
               {"calendar", "standard"}});
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

  void define_series(const std::vector<Gauge>& gauges, detail::NetcdfIds& ids) const {
    int series_dim = -1;
    ok(nc_def_dim(ncid_, "series_time", NC_UNLIMITED, &series_dim), "define dimension series_time");
    ids.series_time = time_variable("series_time", series_dim,
                                    "simulated time of the gauge and volume-balance samples");
    const std::array balance_dims{series_dim};
    ids.in_domain =
        series_var("volume_in_domain", balance_dims, 1, "m3", "volume of water in the domain");
    ids.inflow =
        series_var("volume_inflow", balance_dims, 1, "m3", "cumulative volume that flowed in");
    ids.outflow = series_var("volume_outflow", balance_dims, 1, "m3",
                             "cumulative volume that flowed out or was removed");
    ids.error = series_var("volume_error", balance_dims, 1, "1",
                           "relative volume balance error: (in domain - (initial + inflow - "
                           "outflow)) / reference volume");
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
    ids.gauge_u =
        series_var("gauge_u", dims, n, "m s-1", "depth-averaged velocity along x at the gauge");
    ids.gauge_v =
        series_var("gauge_v", dims, n, "m s-1", "depth-averaged velocity along y at the gauge");
    for (const int id : {ids.gauge_depth, ids.gauge_u, ids.gauge_v}) {
      text(id, "coordinates", "gauge_x gauge_y gauge_name");
      if (georeferenced()) text(id, "grid_mapping", "crs");
    }
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
      ids.gauge_u = variable("gauge_u");
      ids.gauge_v = variable("gauge_v");
    }

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

void validate(const Layout& layout, const std::filesystem::path& path) {
  const Grid& g = layout.grid;
  // A zero length would silently turn x or y into a second unlimited dimension.
  if (g.nx == 0 || g.ny == 0) {
    throw std::invalid_argument("NetcdfWriter: grid for " + quoted(path) +
                                " must have at least one cell in x and y");
  }
  std::set<std::string> names;
  for (const Gauge& gauge : layout.gauges) {
    if (gauge.name.empty()) {
      throw std::invalid_argument("NetcdfWriter: a gauge for " + quoted(path) + " has no name");
    }
    if (!names.insert(gauge.name).second) {
      throw std::invalid_argument("NetcdfWriter: gauge name '" + gauge.name + "' for " +
                                  quoted(path) + " is used twice");
    }
    if (!std::isfinite(gauge.x) || !std::isfinite(gauge.y)) {
      throw std::invalid_argument("NetcdfWriter: gauge '" + gauge.name + "' for " + quoted(path) +
                                  " has a non-finite position");
    }
  }
}

}  // namespace

NetcdfWriter::NetcdfWriter(std::filesystem::path path, const Layout& layout,
                           const RunMetadata& meta)
    : path_(std::move(path)), layout_(layout) {
  validate(layout_, path_);
  partial_path_ = path_;
  partial_path_ += ".partial";

  ncid_ = create_netcdf4(partial_path_);
  try {
    ids_ = Definer{ncid_, partial_path_, layout_.grid}.define(layout_, meta);
  } catch (...) {
    // The destructor does not run for a half-built object; close here, and remove the
    // file since it holds no output at all.
    nc_close(ncid_);
    ncid_ = -1;
    std::error_code ignored;
    std::filesystem::remove(partial_path_, ignored);
    throw;
  }
}

NetcdfWriter::NetcdfWriter(std::filesystem::path path, const Layout& layout,
                           const RunMetadata& meta, const WriterPosition& position)
    : path_(std::move(path)), layout_(layout) {
  validate(layout_, path_);
  partial_path_ = path_;
  partial_path_ += ".partial";
  const int status = nc_open(partial_path_.c_str(), NC_WRITE, &ncid_);
  if (status != NC_NOERR) {
    ncid_ = -1;
    throw std::runtime_error("netCDF: cannot open the file " + quoted(partial_path_) +
                             " to continue it: " + nc_strerror(status));
  }
  try {
    const Resumer resumer{ncid_, partial_path_};
    ids_ = resumer.find(layout_, position);
    bed_written_ = resumer.has_variable("bed_elevation");
    // CF's history is a list of the commands that made the file, one a line.
    std::string history = resumer.text_attribute("history");
    if (!history.empty()) history += '\n';
    history += meta.history;
    const Definer def{ncid_, partial_path_, layout_.grid};
    def.redefine();
    def.text(NC_GLOBAL, "history", history);
    def.end_define();
  } catch (...) {
    nc_close(ncid_);
    ncid_ = -1;
    throw;
  }
  records_ = position.records;
  series_records_ = position.series_records;
  particle_samples_ = position.particle_samples;
}

NetcdfWriter::~NetcdfWriter() {
  // Closing flushes what was written so far, which may help diagnose a failed run; the
  // name stays .partial so nobody mistakes it for a complete result.
  if (ncid_ >= 0) nc_close(ncid_);
}

void NetcdfWriter::require_open(const char* caller) const {
  if (ncid_ < 0) {
    throw std::logic_error(std::string("NetcdfWriter::") + caller + ": " + quoted(path_) +
                           " is already finished");
  }
}

void NetcdfWriter::require_grid_sized(std::span<const double> field, const char* caller,
                                      const char* name) const {
  const std::size_t cells = layout_.grid.nx * layout_.grid.ny;
  if (field.size() != cells) {
    throw std::invalid_argument(std::string("NetcdfWriter::") + caller + ": " + name + " for " +
                                quoted(path_) + " has " + std::to_string(field.size()) +
                                " values, expected " + std::to_string(cells));
  }
}

void NetcdfWriter::write_maps(double time_s, const MapFields& fields) {
  require_grid_sized(fields.depth, "write", "depth");
  require_grid_sized(fields.surface_elevation, "write", "surface_elevation");
  require_grid_sized(fields.u, "write", "u");
  require_grid_sized(fields.v, "write", "v");
  const auto ok = [this](int status, const char* purpose) {
    check(status, purpose, partial_path_);
  };
  const std::size_t rec = records_;
  ok(nc_put_var1_double(ncid_, ids_.time, &rec, &time_s), "write variable time");

  const std::array<std::size_t, 3> start{rec, 0, 0};
  const std::array<std::size_t, 3> count{1, layout_.grid.ny, layout_.grid.nx};
  const struct {
    int varid;
    std::span<const double> values;
    const char* purpose;
  } map_fields[] = {{ids_.depth, fields.depth, "write variable depth"},
                    {ids_.surface, fields.surface_elevation, "write variable surface_elevation"},
                    {ids_.u, fields.u, "write variable u"},
                    {ids_.v, fields.v, "write variable v"}};
  for (const auto& m : map_fields) {
    const std::vector<float> stored = to_stored_floats(m.values);
    ok(nc_put_vara_float(ncid_, m.varid, start.data(), count.data(), stored.data()), m.purpose);
  }
}

void NetcdfWriter::write(double time_s, const MapFields& fields) {
  require_open("write");
  if (layout_.particles) {
    throw std::logic_error("NetcdfWriter::write: " + quoted(path_) +
                           " is laid out with particles; pass them with the maps");
  }
  write_maps(time_s, fields);
  ++records_;
}

void NetcdfWriter::write(double time_s, const particles::SweParticles& p, const MapFields& fields) {
  require_open("write");
  const std::size_t n = p.fluid_count();
  if (layout_.particles && n > static_cast<std::size_t>(INT_MAX)) {
    throw std::invalid_argument("NetcdfWriter::write: too many particles for " + quoted(path_));
  }
  write_maps(time_s, fields);
  if (layout_.particles) {
    const auto ok = [this](int status, const char* purpose) {
      check(status, purpose, partial_path_);
    };
    const std::size_t rec = records_;
    const int count_value = static_cast<int>(n);
    ok(nc_put_var1_int(ncid_, ids_.count, &rec, &count_value), "write variable particle_count");
    // Fluid particles form the prefix of every field, so each field is a single slab.
    const struct {
      int varid;
      const std::vector<double>& values;
      const char* purpose;
    } particle_fields[] = {{ids_.px, p.x, "write variable particle_x"},
                           {ids_.py, p.y, "write variable particle_y"},
                           {ids_.pu, p.u, "write variable particle_u"},
                           {ids_.pv, p.v, "write variable particle_v"},
                           {ids_.ph, p.depth, "write variable particle_depth"},
                           {ids_.pvol, p.volume, "write variable particle_volume"},
                           {ids_.parea, p.area, "write variable particle_area"}};
    if (n > 0) {
      for (const auto& f : particle_fields) {
        ok(nc_put_vara_double(ncid_, f.varid, &particle_samples_, &n, f.values.data()), f.purpose);
      }
    }
    particle_samples_ += n;
  }
  ++records_;
}

void NetcdfWriter::write_series(double time_s, std::span<const GaugeSample> gauges,
                                const BalanceSample& balance) {
  require_open("write_series");
  const std::size_t n = layout_.gauges.size();
  if (gauges.size() != n) {
    throw std::invalid_argument("NetcdfWriter::write_series: " + std::to_string(gauges.size()) +
                                " gauge samples for " + quoted(path_) + ", expected " +
                                std::to_string(n));
  }
  const auto ok = [this](int status, const char* purpose) {
    check(status, purpose, partial_path_);
  };
  const std::size_t rec = series_records_;
  ok(nc_put_var1_double(ncid_, ids_.series_time, &rec, &time_s), "write variable series_time");
  const struct {
    int varid;
    double value;
    const char* purpose;
  } balance_values[] = {{ids_.in_domain, balance.in_domain_m3, "write variable volume_in_domain"},
                        {ids_.inflow, balance.inflow_m3, "write variable volume_inflow"},
                        {ids_.outflow, balance.outflow_m3, "write variable volume_outflow"},
                        {ids_.error, balance.relative_error, "write variable volume_error"}};
  for (const auto& b : balance_values) {
    const double stored = to_stored(b.value);
    ok(nc_put_var1_double(ncid_, b.varid, &rec, &stored), b.purpose);
  }

  if (n > 0) {
    std::vector<double> depth(n), u(n), v(n);
    for (std::size_t i = 0; i < n; ++i) {
      depth[i] = to_stored(gauges[i].depth_m);
      u[i] = to_stored(gauges[i].u_m_s);
      v[i] = to_stored(gauges[i].v_m_s);
    }
    const std::array<std::size_t, 2> start{rec, 0}, count{1, n};
    ok(nc_put_vara_double(ncid_, ids_.gauge_depth, start.data(), count.data(), depth.data()),
       "write variable gauge_depth");
    ok(nc_put_vara_double(ncid_, ids_.gauge_u, start.data(), count.data(), u.data()),
       "write variable gauge_u");
    ok(nc_put_vara_double(ncid_, ids_.gauge_v, start.data(), count.data(), v.data()),
       "write variable gauge_v");
  }
  ++series_records_;
}

void NetcdfWriter::write_bed(std::span<const double> bed_m) {
  require_open("write_bed");
  if (bed_written_) {
    throw std::logic_error("NetcdfWriter::write_bed: the bed of " + quoted(path_) +
                           " is already written");
  }
  require_grid_sized(bed_m, "write_bed", "bed elevation");
  const Definer def{ncid_, partial_path_, layout_.grid};
  def.redefine();
  // CF's name for the height of the ground (the lower boundary of the atmosphere) above
  // the geoid; the datum is in fact the terrain model's.
  const int id = def.static_map_var(ids_, "bed_elevation", "m", "surface_altitude",
                                    "bed (ground) elevation of the terrain model at cell centres");
  def.end_define();
  const std::vector<float> stored = to_stored_floats(bed_m);
  check(nc_put_var_float(ncid_, id, stored.data()), "write variable bed_elevation", partial_path_);
  bed_written_ = true;
}

void NetcdfWriter::write_summary(const maps::FloodStatistics& stats) {
  require_open("write_summary");
  if (summary_written_) {
    throw std::logic_error("NetcdfWriter::write_summary: the summary of " + quoted(path_) +
                           " is already written");
  }
  const std::size_t cells = layout_.grid.nx * layout_.grid.ny;
  if (stats.cells() != cells) {
    throw std::invalid_argument("NetcdfWriter::write_summary: statistics for " + quoted(path_) +
                                " cover " + std::to_string(stats.cells()) + " cells, expected " +
                                std::to_string(cells));
  }
  const Definer def{ncid_, partial_path_, layout_.grid};
  const Resumer existing{ncid_, partial_path_};
  const std::string wet_rule = "wet: depth > " + exact_text(stats.wet_depth()) + " m";
  const std::string velocity_rule =
      wet_rule + "; over wet samples with velocity only (0 where never wet)";
  const struct {
    const char* name;
    std::span<const double> values;
    const char* units;
    const char* standard_name;
    const char* long_name;
    const char* cell_methods;
    std::string comment;
  } summary[] = {
      {"max_depth", stats.max_depth(), "m", "flood_water_thickness",
       "maximum water depth over the run", "time: maximum", "over all samples with data"},
      {"max_speed", stats.max_speed(), "m s-1", nullptr,
       "maximum depth-averaged speed over the run", "time: maximum", velocity_rule},
      {"max_hazard", stats.max_hazard(), "m2 s-1", nullptr,
       "maximum of depth times speed (hazard) over the run", "time: maximum", velocity_rule},
      {"arrival_time", stats.arrival_time(), "s", nullptr,
       "simulated time of the first sample at which the cell was wet", nullptr,
       wet_rule + "; fill value where never wet"},
      {"inundation_duration", stats.inundation_duration(), "s", nullptr, "time the cell was wet",
       nullptr,
       wet_rule + "; a cell wet at sample k counts as wet over (t_{k-1}, t_k], the first "
                  "sample counts nothing"}};
  def.redefine();
  std::array<int, std::size(summary)> ids{};
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const auto& s = summary[k];
    // A resumed file may hold the summary the stopped run wrote; it is replaced.
    ids[k] = existing.optional_variable(s.name);
    if (ids[k] < 0)
      ids[k] = def.static_map_var(ids_, s.name, s.units, s.standard_name, s.long_name);
    if (s.cell_methods) def.text(ids[k], "cell_methods", s.cell_methods);
    def.text(ids[k], "comment",
             "from sample_count samples of the gridded fields; fill value where the cell "
             "never had data; " +
                 s.comment);
    def.number(ids[k], "wet_depth_threshold_m", stats.wet_depth());
    def.integer(ids[k], "sample_count", stats.samples());
  }
  def.end_define();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::vector<float> stored = to_stored_floats(summary[k].values);
    check(nc_put_var_float(ncid_, ids[k], stored.data()),
          std::string("write variable ") + summary[k].name, partial_path_);
  }
  summary_written_ = true;
}

void NetcdfWriter::write_status(const std::string& status, const std::string& message) {
  require_open("write_status");
  const Definer def{ncid_, partial_path_, layout_.grid};
  def.redefine();
  def.text(NC_GLOBAL, "run_status", status);
  if (!message.empty()) {
    def.text(NC_GLOBAL, "run_status_message", message);
  } else {
    // A resumed run that completes drops the message of the stop it continued from.
    const int removed = nc_del_att(ncid_, NC_GLOBAL, "run_status_message");
    if (removed != NC_ENOTATT) check(removed, "remove attribute run_status_message", partial_path_);
  }
  def.end_define();
}

void NetcdfWriter::flush() {
  require_open("flush");
  check(nc_sync(ncid_), "write the file to disk", partial_path_);
}

void NetcdfWriter::close_partial() {
  require_open("close_partial");
  const int status = nc_close(ncid_);
  ncid_ = -1;
  check(status, "close the file", partial_path_);
}

void NetcdfWriter::finish() {
  require_open("finish");
  const int status = nc_close(ncid_);
  // Whatever happened, the handle is gone; a second close would act on a stale id.
  ncid_ = -1;
  check(status, "close the file", partial_path_);

  // Replaces an older result at the final name in one step.
  std::error_code ec;
  std::filesystem::rename(partial_path_, path_, ec);
  if (ec) {
    throw std::runtime_error("NetcdfWriter: cannot rename " + quoted(partial_path_) + " to " +
                             quoted(path_) + ": " + ec.message());
  }
}

}  // namespace swemps::io
