#pragma once
// CF-1.8 netCDF-4 flood-map output of a run, laid out for GIS and array readers (GDAL,
// QGIS, xarray, Panoply):
// - maps per output time on a regular grid (dimension `time`): depth, water-surface
//   elevation and depth-averaged velocity;
// - whole-run summary maps, written once (max depth, speed and hazard, arrival time,
//   inundation duration) and the bed elevation, written once;
// - time series on their own time axis (`series_time`): depth and velocity at gauges, and
//   the volume balance of the domain;
// - optionally the particles themselves, as CF contiguous ragged arrays.
// With a CRS the grid is georeferenced through a `crs` grid-mapping variable. The file is
// written under a temporary name (<path>.partial) and renamed to <path> only by finish(),
// so a run that crashes never leaves a file that looks complete. A run that stops early
// closes it with close_partial() instead, and a run restarted from a checkpoint goes on
// writing it (the resuming constructor).

#include <cstddef>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "swemps/maps/flood_statistics.hpp"
#include "swemps/maps/provenance_maxima.hpp"
#include "swemps/particles/swe_particles.hpp"

namespace swemps::io {

// Regular grid of cell centres: x_i = x0 + i dx (i < nx), y_k = y0 + k dy (k < ny).
struct Grid {
  double x0 = 0.0, y0 = 0.0;  // m, first cell centre
  double dx = 0.0, dy = 0.0;  // m
  std::size_t nx = 0, ny = 0;
  // WKT (any version GDAL reads) of the projected CRS that x and y are in, with metres as
  // its unit; empty for local coordinates in metres without a CRS.
  std::string crs_wkt;
};

struct RunMetadata {
  std::string title;          // global attribute "title"
  std::string scenario_file;  // global attribute "source"
  std::string history;        // global attribute "history": when, and the command line
  double gravity_m_s2 = 9.81;
  // Provenance, each a global attribute of its name unless empty: "program" (name and
  // version), "scenario" (the scene as read, defaults filled in, as JSON), "command_line",
  // "run_started" (wall-clock UTC, ISO 8601) and "time_coverage_start" (the real date and time
  // of t = 0, ISO 8601, when the scene gives one).
  std::string program, scene_json, command_line, run_started, start_time;
  // The units of the time axes: seconds since the scene's start time, or since a nominal epoch.
  std::string time_units = "seconds since 1970-01-01 00:00:00";
};

// A point where depth and velocity are recorded at every series sample.
struct Gauge {
  std::string name;         // unique, not empty: the gauge's id in the file
  double x = 0.0, y = 0.0;  // m, in the grid's coordinates
};

struct Layout {
  Grid grid;
  bool particles = true;      // write the particles at every output time
  std::vector<Gauge> gauges;  // may be empty: then the file has no gauge variables
  // The depth map's long_name: how the depth was measured (the shallow-water cell averages,
  // or the Navier-Stokes column of particles).
  std::string depth_long_name =
      "water depth: the particles' water in the cell over its area (cell average)";
  // Provenance (docs/provenance.md): the names of the sources of the water, for maps, volume
  // balances and gauge shares per source along a dimension `source` (empty: none); and whether
  // the maps include the water's mean age.
  std::vector<std::string> sources = {};
  bool ages = false;
};

// Gridded fields of one output time: ny * nx values each, row-major with x fastest (index
// k * nx + i, rows by ascending y). NaN means no data and is stored as the fill value.
struct MapFields {
  std::span<const double> depth;              // m
  std::span<const double> surface_elevation;  // m, bed + depth
  std::span<const double> u, v;               // m/s, depth-averaged velocity along x and y
  // With provenance in the layout: per source, its water's depth (m) and its share of the
  // cell's water (source k's map at [k * cells, (k + 1) * cells)); the water's mean age (s).
  std::span<const double> source_depth = {}, source_share = {}, mean_age = {};
};

// One gauge at one series time; NaN where there is no value (dry, or outside the water).
struct GaugeSample {
  double depth_m = 0.0;
  double u_m_s = 0.0, v_m_s = 0.0;
  double surface_m = std::numeric_limits<double>::quiet_NaN();  // bed + depth; NaN where dry
  // With sources in the layout: the share of each source in the water at the gauge (NaN where
  // dry), one per source.
  std::vector<double> source_share = {};
};

// Volume balance at one series time.
struct BalanceSample {
  double in_domain_m3 = 0.0;  // water in the domain now
  double inflow_m3 = 0.0;     // cumulative since the start
  double rain_m3 = 0.0;       // cumulative since the start: rain that reached the water
  double outflow_m3 = 0.0;    // cumulative since the start
  // (in_domain - (initial + inflow + rain - outflow)) / reference volume, computed by the
  // caller.
  double relative_error = 0.0;
  // With sources in the layout, one value per source: its water in the domain, what came in
  // after the start (inflow and rain), what left, and its relative balance error.
  std::span<const double> source_in_domain_m3 = {}, source_inflow_m3 = {}, source_outflow_m3 = {},
                          source_relative_error = {};
};

// How much of a file has been written: where a resumed writer goes on.
struct WriterPosition {
  std::size_t records = 0;           // map times
  std::size_t series_records = 0;    // series times
  std::size_t particle_samples = 0;  // particles over all map times
};

namespace detail {
// Dimension and variable ids of an open file; -1 where absent.
struct NetcdfIds {
  int y_dim = -1, x_dim = -1;
  int time = -1, depth = -1, surface = -1, u = -1, v = -1;
  int count = -1, px = -1, py = -1, pu = -1, pv = -1, ph = -1, pvol = -1, parea = -1;
  int series_time = -1, gauge_depth = -1, gauge_surface = -1, gauge_u = -1, gauge_v = -1;
  int in_domain = -1, inflow = -1, rain = -1, outflow = -1, error = -1;
  int source_depth = -1, source_share = -1, mean_age = -1;
  int source_in_domain = -1, source_inflow = -1, source_outflow = -1, source_error = -1;
  int gauge_source_share = -1;
};
}  // namespace detail

class NetcdfWriter {
 public:
  // Creates <path>.partial (netCDF-4), defines dimensions and variables. Throws
  // std::invalid_argument for an empty grid, a CRS that is not projected in metres, or
  // gauges with empty or repeated names or non-finite positions; std::runtime_error naming
  // the file and netCDF's message if the file cannot be written.
  NetcdfWriter(std::filesystem::path path, const Layout& layout, const RunMetadata& meta);
  // Opens <path>.partial, left by an earlier writer of the same layout that stopped at or after
  // `position`, to go on writing after `position`: records past it (written after a
  // checkpoint, before a crash) are overwritten. The command line is added to the history
  // attribute. Throws std::runtime_error naming the file if it cannot be opened, or if its
  // grid, gauges or particle layout differ from `layout` or it holds fewer records than
  // `position`.
  NetcdfWriter(std::filesystem::path path, const Layout& layout, const RunMetadata& meta,
               const WriterPosition& position);
  ~NetcdfWriter();  // closes the file if still open; leaves .partial in place
  NetcdfWriter(const NetcdfWriter&) = delete;
  NetcdfWriter& operator=(const NetcdfWriter&) = delete;

  // Appends one output time of the maps and, if enabled, the fluid particles of `p`.
  void write(double time_s, const particles::SweParticles& p, const MapFields& fields);
  // Appends one output time of the maps alone, for a layout without particles (throws
  // std::logic_error otherwise: the particle records would fall out of step with the maps).
  void write(double time_s, const MapFields& fields);

  // Appends one series time: one sample per gauge, in the order given at construction.
  void write_series(double time_s, std::span<const GaugeSample> gauges,
                    const BalanceSample& balance);

  // The bed elevation (m, ny * nx values laid out as in MapFields); at most once.
  void write_bed(std::span<const double> bed_m);

  // The whole-run summary maps; at most once, before finish(). The statistics must cover
  // the grid's cells.
  void write_summary(const maps::FloodStatistics& stats);
  // The whole-run maxima of the provenance maps (layout sources and ages), with the summary;
  // rewritten by each call (a run that stops, goes on and finishes).
  void write_provenance_summary(const maps::ProvenanceMaxima& maxima);

  // The global attributes run_status ("complete", "interrupted", "breakdown", "failed")
  // and, unless empty, run_status_message; rewritten by each call.
  void write_status(const std::string& status, const std::string& message);

  // Hands what was written so far to the operating system, so that the file on disk holds it
  // even if the process is killed before closing it (done before each checkpoint).
  void flush();

  // Closes the file and renames <path>.partial to <path>. Variables written once that
  // were never written are absent from the file rather than full of fill values.
  void finish();
  // Closes the file and leaves it at <path>.partial: a run that stopped before its end, whose
  // file is readable but incomplete, and may be resumed.
  void close_partial();

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& partial_path() const { return partial_path_; }
  std::size_t records() const { return records_; }
  std::size_t series_records() const { return series_records_; }
  bool bed_written() const { return bed_written_; }
  WriterPosition position() const { return {records_, series_records_, particle_samples_}; }

 private:
  void require_open(const char* caller) const;
  void require_grid_sized(std::span<const double> field, const char* caller,
                          const char* name) const;
  void write_maps(double time_s, const MapFields& fields);
  void write_provenance_maps(const MapFields& fields);
  void write_provenance_series(std::span<const GaugeSample> gauges, const BalanceSample& balance);

  std::filesystem::path path_, partial_path_;
  int ncid_ = -1;
  Layout layout_;
  std::size_t records_ = 0;
  std::size_t series_records_ = 0;
  std::size_t particle_samples_ = 0;
  bool bed_written_ = false, summary_written_ = false;
  detail::NetcdfIds ids_;
};

}  // namespace swemps::io
