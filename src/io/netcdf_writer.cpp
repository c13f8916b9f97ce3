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

#include "netcdf_layout.hpp"
#include "swemps/io/gdal_messages.hpp"

namespace swemps::io {

using namespace netcdf;

namespace {

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
    def.put_provenance(meta);
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
  write_provenance_maps(fields);
}

void NetcdfWriter::write_provenance_maps(const MapFields& fields) {
  const auto ok = [this](int status, const char* purpose) {
    check(status, purpose, partial_path_);
  };
  const std::size_t rec = records_;
  if (layout_.ages) {
    require_grid_sized(fields.mean_age, "write", "mean_age");
    const std::array<std::size_t, 3> start{rec, 0, 0};
    const std::array<std::size_t, 3> count{1, layout_.grid.ny, layout_.grid.nx};
    const std::vector<float> stored = to_stored_floats(fields.mean_age);
    ok(nc_put_vara_float(ncid_, ids_.mean_age, start.data(), count.data(), stored.data()),
       "write variable mean_age");
  }
  const std::size_t sources = layout_.sources.size();
  if (sources == 0) return;
  const std::size_t cells = layout_.grid.nx * layout_.grid.ny;
  for (const auto& [values, name] : {std::pair{fields.source_depth, "source_depth"},
                                     std::pair{fields.source_share, "source_share"}}) {
    if (values.size() != sources * cells) {
      throw std::invalid_argument(std::string("NetcdfWriter::write: ") + name + " for " +
                                  quoted(path_) + " has " + std::to_string(values.size()) +
                                  " values, expected " + std::to_string(sources * cells));
    }
  }
  const std::array<std::size_t, 4> start{rec, 0, 0, 0};
  const std::array<std::size_t, 4> count{1, sources, layout_.grid.ny, layout_.grid.nx};
  const std::vector<float> depth = to_stored_floats(fields.source_depth);
  ok(nc_put_vara_float(ncid_, ids_.source_depth, start.data(), count.data(), depth.data()),
     "write variable source_depth");
  const std::vector<float> share = to_stored_floats(fields.source_share);
  ok(nc_put_vara_float(ncid_, ids_.source_share, start.data(), count.data(), share.data()),
     "write variable source_share");
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
                        {ids_.rain, balance.rain_m3, "write variable volume_rain"},
                        {ids_.outflow, balance.outflow_m3, "write variable volume_outflow"},
                        {ids_.error, balance.relative_error, "write variable volume_error"}};
  for (const auto& b : balance_values) {
    const double stored = to_stored(b.value);
    ok(nc_put_var1_double(ncid_, b.varid, &rec, &stored), b.purpose);
  }

  if (n > 0) {
    std::vector<double> depth(n), surface(n), u(n), v(n);
    for (std::size_t i = 0; i < n; ++i) {
      depth[i] = to_stored(gauges[i].depth_m);
      surface[i] = to_stored(gauges[i].surface_m);
      u[i] = to_stored(gauges[i].u_m_s);
      v[i] = to_stored(gauges[i].v_m_s);
    }
    const std::array<std::size_t, 2> start{rec, 0}, count{1, n};
    ok(nc_put_vara_double(ncid_, ids_.gauge_depth, start.data(), count.data(), depth.data()),
       "write variable gauge_depth");
    ok(nc_put_vara_double(ncid_, ids_.gauge_surface, start.data(), count.data(), surface.data()),
       "write variable gauge_surface_elevation");
    ok(nc_put_vara_double(ncid_, ids_.gauge_u, start.data(), count.data(), u.data()),
       "write variable gauge_u");
    ok(nc_put_vara_double(ncid_, ids_.gauge_v, start.data(), count.data(), v.data()),
       "write variable gauge_v");
  }
  write_provenance_series(gauges, balance);
  ++series_records_;
}

void NetcdfWriter::write_provenance_series(std::span<const GaugeSample> gauges,
                                           const BalanceSample& balance) {
  const std::size_t sources = layout_.sources.size();
  if (sources == 0) return;
  const auto ok = [this](int status, const char* purpose) {
    check(status, purpose, partial_path_);
  };
  const std::size_t rec = series_records_;
  const struct {
    int varid;
    std::span<const double> values;
    const char* name;
  } books[] = {{ids_.source_in_domain, balance.source_in_domain_m3, "source_volume_in_domain"},
               {ids_.source_inflow, balance.source_inflow_m3, "source_volume_inflow"},
               {ids_.source_outflow, balance.source_outflow_m3, "source_volume_outflow"},
               {ids_.source_error, balance.source_relative_error, "source_volume_error"}};
  const std::array<std::size_t, 2> start{rec, 0}, count{1, sources};
  for (const auto& b : books) {
    if (b.values.size() != sources) {
      throw std::invalid_argument(std::string("NetcdfWriter::write_series: ") + b.name + " for " +
                                  quoted(path_) + " has " + std::to_string(b.values.size()) +
                                  " values, expected " + std::to_string(sources));
    }
    std::vector<double> stored(sources);
    for (std::size_t k = 0; k < sources; ++k) stored[k] = to_stored(b.values[k]);
    ok(nc_put_vara_double(ncid_, b.varid, start.data(), count.data(), stored.data()),
       (std::string("write variable ") + b.name).c_str());
  }
  if (gauges.empty()) return;
  std::vector<double> shares;
  for (const GaugeSample& g : gauges) {
    if (g.source_share.size() != sources) {
      throw std::invalid_argument("NetcdfWriter::write_series: a gauge sample for " +
                                  quoted(path_) + " has " + std::to_string(g.source_share.size()) +
                                  " source shares, expected " + std::to_string(sources));
    }
    for (const double s : g.source_share) shares.push_back(to_stored(s));
  }
  const std::array<std::size_t, 3> gauge_start{rec, 0, 0}, gauge_count{1, gauges.size(), sources};
  ok(nc_put_vara_double(ncid_, ids_.gauge_source_share, gauge_start.data(), gauge_count.data(),
                        shares.data()),
     "write variable gauge_source_share");
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
