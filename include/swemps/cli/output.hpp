#pragma once
// What a run writes, whichever model made it: the netCDF file of maps, gauges, volume balance
// and flood statistics (io::NetcdfWriter), and CSV tables beside it. Both are written under
// <path>.partial and renamed when complete; every write failure becomes OutputError.

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "swemps/cli/run_command.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

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

// Where a run comes from, for the files' metadata.
struct RunContext {
  std::filesystem::path scenario_file;
  std::string command_line;
  bool progress = true;  // draw the progress bar (not with -q)
};

// Gridded fields of one state on the output grid: ny * nx values each, x fastest.
struct GriddedState {
  std::span<const double> depth;  // m
  std::span<const double> u, v;   // m/s, depth-averaged; NaN where unknown
};

// The netCDF file of a run, with the flood statistics gathered from its samples.
class MapOutput {
 public:
  // `particles`: whether the SWE particles are written with the maps. `depth_long_name` says
  // how depth was measured (empty: the shallow-water summation); `title_note` is added to the
  // file's title (the model).
  MapOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain,
            const swe::RegularGrid& grid, const RunContext& context, bool particles,
            const std::string& depth_long_name, const std::string& title_note);

  // The maps at an output time: depth everywhere; water surface and velocity only where the
  // cell is wetter than the scene's wet depth (over a thinner film they are noise).
  // `particles` is written when the layout has particles, and must then be given.
  void write_maps(double time_s, const GriddedState& state,
                  const particles::SweParticles* particles = nullptr);

  // One series sample: the gauges, the volume balance and the flood statistics.
  void sample(double time_s, const GriddedState& state, std::span<const io::GaugeSample> gauges,
              const io::BalanceSample& balance);

  void finish();  // summary maps, then the file gets its final name

  const std::filesystem::path& path() const { return writer_->path(); }
  double wet_depth_m() const { return wet_depth_m_; }

 private:
  double wet_depth_m_;
  std::vector<double> bed_m_;  // at cell centres; 0 without a bed
  maps::FloodStatistics statistics_;
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

// A column name that spreadsheet and data-frame readers take as it is: letters, digits, '_',
// '-' and '.' kept, anything else (spaces, commas, quotes) replaced by '_'.
std::string column_name(const std::string& text);

}  // namespace swemps::cli
