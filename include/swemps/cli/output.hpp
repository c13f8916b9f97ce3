#pragma once
// What a run writes, whichever model made it: the netCDF file of maps, gauges, volume balance
// and flood statistics (io::NetcdfWriter), and CSV tables beside it. Both are written under
// <path>.partial and renamed when complete; every write failure becomes OutputError.

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "swemps/cli/run_command.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/io/tsunami_products.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/state_record.hpp"

namespace swemps::cli {

// Runs a writer call, turning its failures into OutputError: I/O trouble (runtime_error) and
// what the writer refuses to write (invalid_argument), such as a CRS it cannot store.
template <class Call>
void writing(Call&& call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  } catch (const std::invalid_argument& e) {
    throw OutputError(e.what());
  }
}

// Where a run comes from, for the files' metadata, and how it is to be run.
struct RunContext {
  std::filesystem::path scenario_file;
  std::string command_line;
  bool progress = true;  // draw the progress bar (not with -q)
  // Write checkpoints (checkpoint_path()) when the run stops early and, if checkpoint_every >
  // 0, every checkpoint_every output times; go on from `restart`. Off for the runs of compare
  // and study, whose files are not meant to be continued.
  bool checkpoints = false;
  int checkpoint_every = 0;
  std::optional<std::filesystem::path> restart = std::nullopt;
};

// The context of `swe-mps run` for the scene: checkpoints on, and the options' restart and
// checkpoint interval, for either model.
RunContext run_context(const Options& options, const std::string& command_line,
                       const scenario::Scenario& scene);

// Where a run writing `output` keeps its checkpoint: the same path with the extension
// .checkpoint ("flood.nc" -> "flood.checkpoint").
std::filesystem::path checkpoint_path(const std::filesystem::path& output);

// Gridded fields of one state on the output grid: ny * nx values each, x fastest.
struct GriddedState {
  std::span<const double> depth;  // m
  std::span<const double> u, v;   // m/s, depth-averaged; NaN where unknown
  // Provenance, when the scene asks for it (maps::CellFields): per source, its water's depth;
  // the mean time the water entered the domain. Empty otherwise.
  std::span<const double> source_depth = {}, entry_time = {};
};

// The tsunami products of a finished result beside it (io/tsunami_products.hpp): the
// inundation line as <prefix>_inundation_line.gpkg or .geojson (none with `line` empty) and,
// where the result has tsunami maps and gauges, <prefix>_gauge_arrivals.csv; each file
// written and the run-up reached are logged. OutputError on failure.
void write_tsunami_products(const std::filesystem::path& result,
                            const std::filesystem::path& prefix,
                            std::optional<io::VectorFile> line);

// The netCDF file of a run, with the flood statistics gathered from its samples.
class MapOutput {
 public:
  // `particles`: whether the SWE particles are written with the maps. `depth_long_name` says
  // how depth was measured (empty: the shallow-water cell averages); `title_note` is added to
  // the file's title (the model).
  // With `resume`, goes on writing <output>.partial after that position (a run restarted from
  // a checkpoint); throws io::CheckpointError if that file cannot be opened or does not match
  // the checkpoint: the checkpoint cannot be used without the maps written before it.
  MapOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain,
            const swe::RegularGrid& grid, const RunContext& context, bool particles,
            const std::string& depth_long_name, const std::string& title_note,
            const std::optional<io::WriterPosition>& resume = std::nullopt);

  // The maps at an output time: depth everywhere; water surface and velocity only where the
  // cell is wetter than the scene's wet depth (over a thinner film they are noise).
  // `particles` is written when the layout has particles, and must then be given.
  void write_maps(double time_s, const GriddedState& state,
                  const particles::SweParticles* particles = nullptr);

  // The flood statistics take one more sample of the gridded state (a shallow-water run gives
  // every step, the Navier-Stokes mode its series samples).
  void update_statistics(double time_s, const GriddedState& state);
  // One series sample: the gauges and the volume balance.
  void sample_series(double time_s, std::span<const io::GaugeSample> gauges,
                     const io::BalanceSample& balance);

  // Summary maps and run_status "complete", then the file gets its final name; then the
  // scene's GeoTIFF maps and the gauge CSV are made from it (io/flood_products.hpp).
  void finish();
  // For a run that stops early: the summary maps of the samples so far, the status
  // ("interrupted", "breakdown", "failed") and its message; the file is closed and stays
  // <path>.partial.
  void close_stopped(const std::string& status, const std::string& message);
  void flush();  // what is written so far onto the disk (before a checkpoint)

  // Where the file stands and the flood statistics so far, for a checkpoint; restore_state()
  // after construction with the position that save_state() wrote first.
  void save_state(swe::StateWriter& out) const;
  static io::WriterPosition read_position(swe::StateReader& in);
  void restore_statistics(swe::StateReader& in);

  const std::filesystem::path& path() const { return writer_->path(); }
  const std::filesystem::path& partial_path() const { return writer_->partial_path(); }
  double wet_depth_m() const { return wet_depth_m_; }
  // The bed elevation at a point (m; 0 without a bed), for the gauges' water surface.
  double bed_at(double x_m, double y_m) const;

 private:
  double wet_depth_m_;
  std::vector<std::string> rasters_;  // written as GeoTIFF by finish()
  bool raster_cog_;
  std::optional<scenario::TsunamiOutput> tsunami_;  // products made by finish()
  std::shared_ptr<const swe::BedSource> bed_;  // null: flat at z = 0
  std::vector<double> bed_m_;                  // at cell centres; 0 without a bed
  maps::FloodStatistics statistics_;
  maps::ProvenanceMaxima provenance_;  // empty when the scene asks for no provenance
  std::unique_ptr<io::NetcdfWriter> writer_;
};

// A CSV table: a header of column names, then one row of numbers per call. Written to
// <path>.partial and renamed to <path> by finish(), so a file with the final name is whole.
class CsvTable {
 public:
  CsvTable(std::filesystem::path path, std::vector<std::string> columns);
  ~CsvTable();  // closes; leaves .partial in place unless finished
  CsvTable(const CsvTable&) = delete;
  CsvTable& operator=(const CsvTable&) = delete;

  void row(std::span<const double> values);  // one value per column; NaN is written "nan"
  void finish();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_, partial_path_;
  std::size_t columns_;
  std::FILE* file_ = nullptr;
};

}  // namespace swemps::cli
