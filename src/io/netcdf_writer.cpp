#include "swemps/io/netcdf_writer.hpp"

#include <netcdf.h>

#include <array>
#include <climits>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace swemps::io {

namespace {

// Samples per chunk of the particle variables: large enough that compression works on
// whole blocks, small enough that a short run does not allocate a huge first chunk.
constexpr std::size_t kParticleChunk = 65536;

std::string quoted(const std::filesystem::path& p) {
  // Appended piecewise: `"'" + string` trips a false -Wrestrict warning in GCC 12.
  std::string text(1, '\'');
  text += p.string();
  text += '\'';
  return text;
}

// Every netCDF call goes through here so that a failure always reports what was being
// done, to which file, and netCDF's own explanation.
void check(int status, const char* purpose, const std::filesystem::path& file) {
  if (status != NC_NOERR) {
    throw std::runtime_error(std::string("netCDF: cannot ") + purpose + " (file " + quoted(file) +
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

// Ids of the variables written per record; -1 where a variable does not exist.
struct VarIds {
  int time = -1, depth = -1, count = -1;
  int px = -1, py = -1, pu = -1, pv = -1, ph = -1, pvol = -1, parea = -1;
};

// Defines the file's layout and writes the fixed coordinates; kept apart from the writer
// so that the class holds only what is needed while records are appended.
class Definer {
 public:
  Definer(int ncid, const std::filesystem::path& file) : ncid_(ncid), file_(file) {}

  VarIds define(const Grid& grid, const RunMetadata& meta, bool particles) const {
    put_globals(meta);
    int time_dim = -1, y_dim = -1, x_dim = -1;
    ok(nc_def_dim(ncid_, "time", NC_UNLIMITED, &time_dim), "define dimension time");
    ok(nc_def_dim(ncid_, "y", grid.ny, &y_dim), "define dimension y");
    ok(nc_def_dim(ncid_, "x", grid.nx, &x_dim), "define dimension x");

    VarIds ids;
    const int x_var = coordinate("x", x_dim, "X");
    const int y_var = coordinate("y", y_dim, "Y");
    ids.time = def_var("time", NC_DOUBLE, std::array{time_dim});
    texts(ids.time, {{"units", "seconds since 1970-01-01 00:00:00"},
                     {"standard_name", "time"},
                     {"long_name", "simulated time since the start of the run"},
                     {"axis", "T"},
                     {"calendar", "standard"}});
    ids.depth = define_depth(grid, time_dim, y_dim, x_dim);
    if (particles) define_particles(time_dim, ids);
    ok(nc_enddef(ncid_), "leave define mode");

    write_axis(x_var, grid.x0, grid.dx, grid.nx, "write variable x");
    write_axis(y_var, grid.y0, grid.dy, grid.ny, "write variable y");
    return ids;
  }

 private:
  void ok(int status, const std::string& purpose) const { check(status, purpose.c_str(), file_); }

  void text(int varid, const char* name, const std::string& value) const {
    ok(nc_put_att_text(ncid_, varid, name, value.size(), value.c_str()),
       std::string("write attribute ") + name);
  }
  void texts(int varid, std::initializer_list<std::pair<const char*, const char*>> atts) const {
    for (const auto& [name, value] : atts) text(varid, name, value);
  }

  template <std::size_t N>
  int def_var(const char* name, nc_type type, const std::array<int, N>& dims) const {
    int varid = -1;
    ok(nc_def_var(ncid_, name, type, static_cast<int>(N), dims.data(), &varid),
       std::string("define variable ") + name);
    return varid;
  }

  void put_globals(const RunMetadata& meta) const {
    // No institution and no featureType: the file is not a discrete-sampling dataset, and
    // the grid part is what most readers open.
    texts(NC_GLOBAL, {{"Conventions", "CF-1.8"}, {"references", "swe-mps shallow-water MPS"}});
    text(NC_GLOBAL, "title", meta.title);
    text(NC_GLOBAL, "source", meta.scenario_file);
    text(NC_GLOBAL, "history", meta.history);
    ok(nc_put_att_double(ncid_, NC_GLOBAL, "gravity_m_s2", NC_DOUBLE, 1, &meta.gravity_m_s2),
       "write attribute gravity_m_s2");
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

  int define_depth(const Grid& grid, int time_dim, int y_dim, int x_dim) const {
    // Single precision is ample for a map of depths and halves the file size.
    const int id = def_var("depth", NC_FLOAT, std::array{time_dim, y_dim, x_dim});
    const std::array<std::size_t, 3> chunk{1, grid.ny, grid.nx};
    ok(nc_def_var_chunking(ncid_, id, NC_CHUNKED, chunk.data()), "set chunking of depth");
    ok(nc_def_var_deflate(ncid_, id, 1, 1, 4), "set compression of depth");
    // CF's name for the depth of water standing on land (the sea-floor names assume an ocean).
    texts(id, {{"units", "m"},
               {"standard_name", "flood_water_thickness"},
               {"long_name", "water depth (eq 7 summation of the particles at cell centres)"}});
    return id;
  }

  int particle_var(int sample_dim, const char* name, const char* units,
                   const char* long_name) const {
    const int id = def_var(name, NC_DOUBLE, std::array{sample_dim});
    const std::size_t chunk = kParticleChunk;
    ok(nc_def_var_chunking(ncid_, id, NC_CHUNKED, &chunk), std::string("set chunking of ") + name);
    // Light compression: particle output is large and written often, so speed matters more
    // than the last few percent of size; shuffle makes doubles compress far better.
    ok(nc_def_var_deflate(ncid_, id, 1, 1, 1), std::string("set compression of ") + name);
    texts(id, {{"units", units}, {"long_name", long_name}});
    return id;
  }

  void define_particles(int time_dim, VarIds& ids) const {
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

  void write_axis(int varid, double origin, double step, std::size_t n, const char* purpose) const {
    std::vector<double> values(n);
    for (std::size_t i = 0; i < n; ++i) values[i] = origin + static_cast<double>(i) * step;
    ok(nc_put_var_double(ncid_, varid, values.data()), purpose);
  }

  int ncid_;
  const std::filesystem::path& file_;
};

}  // namespace

NetcdfWriter::NetcdfWriter(std::filesystem::path path, const Grid& grid, const RunMetadata& meta,
                           bool write_particles)
    : path_(std::move(path)), write_particles_(write_particles), grid_(grid) {
  // A zero length would silently turn x or y into a second unlimited dimension.
  if (grid_.nx == 0 || grid_.ny == 0) {
    throw std::invalid_argument("NetcdfWriter: grid for " + quoted(path_) +
                                " must have at least one cell in x and y");
  }
  partial_path_ = path_;
  partial_path_ += ".partial";

  ncid_ = create_netcdf4(partial_path_);
  try {
    const Definer def{ncid_, partial_path_};
    const VarIds ids = def.define(grid_, meta, write_particles_);
    time_var_ = ids.time;
    depth_var_ = ids.depth;
    count_var_ = ids.count;
    px_var_ = ids.px;
    py_var_ = ids.py;
    pu_var_ = ids.pu;
    pv_var_ = ids.pv;
    ph_var_ = ids.ph;
    pvol_var_ = ids.pvol;
    parea_var_ = ids.parea;
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

NetcdfWriter::~NetcdfWriter() {
  // Closing flushes what was written so far, which may help diagnose a failed run; the
  // name stays .partial so nobody mistakes it for a complete result.
  if (ncid_ >= 0) nc_close(ncid_);
}

void NetcdfWriter::write(double time_s, const particles::SweParticles& p,
                         std::span<const double> grid_depth) {
  if (ncid_ < 0) {
    throw std::logic_error("NetcdfWriter::write: " + quoted(path_) + " is already finished");
  }
  if (grid_depth.size() != grid_.nx * grid_.ny) {
    throw std::invalid_argument("NetcdfWriter::write: grid depth for " + quoted(path_) + " has " +
                                std::to_string(grid_depth.size()) + " values, expected " +
                                std::to_string(grid_.nx * grid_.ny));
  }
  const std::size_t n = p.fluid_count();
  if (write_particles_ && n > static_cast<std::size_t>(INT_MAX)) {
    throw std::invalid_argument("NetcdfWriter::write: too many particles for " + quoted(path_));
  }
  const auto ok = [this](int status, const char* purpose) {
    check(status, purpose, partial_path_);
  };

  const std::size_t rec = records_;
  ok(nc_put_var1_double(ncid_, time_var_, &rec, &time_s), "write variable time");

  const std::vector<float> depth(grid_depth.begin(), grid_depth.end());
  const std::array<std::size_t, 3> start{rec, 0, 0};
  const std::array<std::size_t, 3> count{1, grid_.ny, grid_.nx};
  ok(nc_put_vara_float(ncid_, depth_var_, start.data(), count.data(), depth.data()),
     "write variable depth");

  if (write_particles_) {
    const int count_value = static_cast<int>(n);
    ok(nc_put_var1_int(ncid_, count_var_, &rec, &count_value), "write variable particle_count");
    // Fluid particles form the prefix of every field, so each field is a single slab.
    struct Field {
      int varid;
      const std::vector<double>& values;
      const char* purpose;
    };
    const Field fields[] = {{px_var_, p.x, "write variable particle_x"},
                            {py_var_, p.y, "write variable particle_y"},
                            {pu_var_, p.u, "write variable particle_u"},
                            {pv_var_, p.v, "write variable particle_v"},
                            {ph_var_, p.depth, "write variable particle_depth"},
                            {pvol_var_, p.volume, "write variable particle_volume"},
                            {parea_var_, p.area, "write variable particle_area"}};
    if (n > 0) {
      for (const Field& f : fields) {
        ok(nc_put_vara_double(ncid_, f.varid, &particle_samples_, &n, f.values.data()), f.purpose);
      }
    }
    particle_samples_ += n;
  }
  ++records_;
}

void NetcdfWriter::finish() {
  if (ncid_ < 0) {
    throw std::logic_error("NetcdfWriter::finish: " + quoted(path_) + " is already finished");
  }
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
