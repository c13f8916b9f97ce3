#include "swemps/cli/output.hpp"

#include <spdlog/fmt/fmt.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <system_error>

#include "swemps/io/checkpoint.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr const char* kOutputStateLabel = "swe-mps map output";

}  // namespace

RunContext run_context(const Options& options, const std::string& command_line,
                       const scenario::Scenario& scene) {
  if (scene.model == scenario::Model::ns && (options.restart || options.checkpoint_every > 0)) {
    throw UsageError("--restart and --checkpoint-every apply to shallow-water scenes only");
  }
  RunContext context{options.scenario, command_line, options.verbosity != Verbosity::quiet};
  context.checkpoints = scene.model == scenario::Model::swe;
  context.checkpoint_every = options.checkpoint_every;
  context.restart = options.restart;
  return context;
}

std::filesystem::path checkpoint_path(const std::filesystem::path& output) {
  std::filesystem::path path = output;
  path.replace_extension(".checkpoint");
  return path;
}

MapOutput::MapOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain,
                     const swe::RegularGrid& grid, const RunContext& context, bool particles,
                     const std::string& depth_long_name, const std::string& title_note,
                     const std::optional<io::WriterPosition>& resume)
    : wet_depth_m_(scene.output.wet_depth_m),
      bed_m_(grid.nx * grid.ny, 0.0),
      statistics_(grid.nx * grid.ny, scene.output.wet_depth_m) {
  io::RunMetadata meta{
      scene.name,
      std::string("swe-mps ") + SWEMPS_VERSION + ", scenario " + context.scenario_file.string(),
      context.command_line, scene.numerics.gravity_m_s2};
  if (!scene.description.empty()) meta.title += ": " + scene.description;
  if (!title_note.empty()) meta.title += " (" + title_note + ")";
  io::Layout layout{
      {grid.x0, grid.y0, grid.dx, grid.dy, grid.nx, grid.ny, terrain.crs_wkt}, particles, {}};
  if (!depth_long_name.empty()) layout.depth_long_name = depth_long_name;
  for (const auto& g : scene.output.gauges) {
    layout.gauges.push_back({g.name, g.position_m[0], g.position_m[1]});
  }
  if (terrain.bed) {
    for (std::size_t k = 0; k < grid.ny; ++k) {
      for (std::size_t i = 0; i < grid.nx; ++i) {
        bed_m_[k * grid.nx + i] = terrain.bed->elevation(
            grid.x0 + static_cast<double>(i) * grid.dx, grid.y0 + static_cast<double>(k) * grid.dy);
      }
    }
  }
  if (resume) {
    try {
      writer_ = std::make_unique<io::NetcdfWriter>(scene.output.path, layout, meta, *resume);
    } catch (const std::exception& e) {
      throw io::CheckpointError(std::string("cannot go on with the output the stopped run left: ") +
                                e.what());
    }
  } else {
    writing([&] { writer_ = std::make_unique<io::NetcdfWriter>(scene.output.path, layout, meta); });
  }
  // A scene without a bed stands on z = 0 everywhere: nothing worth a map.
  if (terrain.bed && !writer_->bed_written()) writing([&] { writer_->write_bed(bed_m_); });
}

void MapOutput::write_maps(double time_s, const GriddedState& state,
                           const particles::SweParticles* particles) {
  const std::size_t cells = state.depth.size();
  std::vector<double> surface(cells, kNaN), u(cells, kNaN), v(cells, kNaN);
  for (std::size_t c = 0; c < cells; ++c) {
    if (!(state.depth[c] > wet_depth_m_)) continue;
    surface[c] = state.depth[c] + bed_m_[c];
    u[c] = state.u[c];
    v[c] = state.v[c];
  }
  const io::MapFields fields{state.depth, surface, u, v};
  writing([&] {
    if (particles != nullptr) {
      writer_->write(time_s, *particles, fields);
    } else {
      writer_->write(time_s, fields);
    }
  });
}

void MapOutput::sample(double time_s, const GriddedState& state,
                       std::span<const io::GaugeSample> gauges, const io::BalanceSample& balance) {
  statistics_.update(time_s, state.depth, state.u, state.v);
  writing([&] { writer_->write_series(time_s, gauges, balance); });
}

void MapOutput::finish() {
  writing([&] {
    writer_->write_summary(statistics_);
    writer_->write_status("complete", "");
    writer_->finish();
  });
}

void MapOutput::close_stopped(const std::string& status, const std::string& message) {
  writing([&] {
    writer_->write_summary(statistics_);
    writer_->write_status(status, message);
    writer_->close_partial();
  });
}

void MapOutput::flush() {
  writing([&] { writer_->flush(); });
}

void MapOutput::save_state(swe::StateWriter& out) const {
  out.text(kOutputStateLabel);
  const io::WriterPosition position = writer_->position();
  for (const std::size_t n :
       {position.records, position.series_records, position.particle_samples}) {
    out.count(n);
  }
  out.count(statistics_.samples());
  out.number(statistics_.last_time());
  for (const auto map : statistics_.maps()) out.numbers(map);
}

io::WriterPosition MapOutput::read_position(swe::StateReader& in) {
  in.expect(kOutputStateLabel);
  io::WriterPosition position;
  position.records = in.count();
  position.series_records = in.count();
  position.particle_samples = in.count();
  return position;
}

void MapOutput::restore_statistics(swe::StateReader& in) {
  const std::size_t samples = in.count();
  const double last_time_s = in.number();
  std::vector<std::vector<double>> maps;
  for (int k = 0; k < 5; ++k) maps.push_back(in.numbers());
  try {
    statistics_.restore(samples, last_time_s, std::move(maps));
  } catch (const std::invalid_argument& e) {
    throw swe::StateError(in.what() + " does not fit this scene's output grid: " + e.what());
  }
}

// ---------------------------------------------------------------------------------------------

CsvTable::CsvTable(std::filesystem::path path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(columns.size()) {
  partial_path_ = path_;
  partial_path_ += ".partial";
  errno = 0;
  file_ = std::fopen(partial_path_.c_str(), "w");
  if (file_ == nullptr) {
    throw OutputError("cannot create the file '" + partial_path_.string() +
                      "': " + (errno != 0 ? std::strerror(errno) : "unknown reason"));
  }
  std::string header;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    if (k > 0) header += ',';
    header += columns[k];
  }
  header += '\n';
  if (std::fputs(header.c_str(), file_) < 0) {
    throw OutputError("cannot write to '" + partial_path_.string() + "'");
  }
}

CsvTable::~CsvTable() {
  if (file_ != nullptr) std::fclose(file_);
}

void CsvTable::row(std::span<const double> values) {
  if (file_ == nullptr) {
    throw std::logic_error("CsvTable::row: '" + path_.string() + "' is already finished");
  }
  if (values.size() != columns_) {
    throw std::logic_error("CsvTable::row: " + std::to_string(values.size()) + " values for " +
                           std::to_string(columns_) + " columns of '" + path_.string() + "'");
  }
  std::string line;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k > 0) line += ',';
    // 12 significant digits keep times and positions exact to far below their meaning.
    line += std::isnan(values[k]) ? std::string("nan") : fmt::format("{:.12g}", values[k]);
  }
  line += '\n';
  if (std::fputs(line.c_str(), file_) < 0) {
    throw OutputError("cannot write to '" + partial_path_.string() + "'");
  }
}

void CsvTable::finish() {
  const int status = std::fclose(file_);
  file_ = nullptr;
  if (status != 0) throw OutputError("cannot close '" + partial_path_.string() + "'");
  std::error_code ec;
  std::filesystem::rename(partial_path_, path_, ec);
  if (ec) {
    throw OutputError("cannot rename '" + partial_path_.string() + "' to '" + path_.string() +
                      "': " + ec.message());
  }
}

std::string column_name(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '_' && c != '-' && c != '.') c = '_';
  }
  return out;
}

}  // namespace swemps::cli
