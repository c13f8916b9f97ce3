#include "swemps/cli/output.hpp"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <system_error>

#include "swemps/io/checkpoint.hpp"
#include "swemps/io/flood_products.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Version 2: the statistics of the flood products (8 maps and 2 a depth threshold, not 5).
constexpr const char* kOutputStateLabel = "swe-mps map output 2";

// Now, in UTC, as ISO 8601 to the second.
std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// The bed elevation at the grid's cell centres; 0 without a bed.
std::vector<double> grid_bed(const scenario::Terrain& terrain, const swe::RegularGrid& grid) {
  std::vector<double> bed(grid.nx * grid.ny, 0.0);
  if (!terrain.bed) return bed;
  for (std::size_t k = 0; k < grid.ny; ++k) {
    for (std::size_t i = 0; i < grid.nx; ++i) {
      bed[k * grid.nx + i] = terrain.bed->elevation(grid.x0 + static_cast<double>(i) * grid.dx,
                                                    grid.y0 + static_cast<double>(k) * grid.dy);
    }
  }
  return bed;
}

}  // namespace

RunContext run_context(const Options& options, const std::string& command_line,
                       const scenario::Scenario& /*scene*/) {
  // Both models write checkpoints and go on from them.
  RunContext context{options.scenario, command_line, options.verbosity != Verbosity::quiet};
  context.checkpoints = true;
  context.checkpoint_every = options.checkpoint_every;
  context.restart = options.restart;
  return context;
}

std::filesystem::path checkpoint_path(const std::filesystem::path& output) {
  std::filesystem::path path = output;
  path.replace_extension(".checkpoint");
  return path;
}

void write_tsunami_products(const std::filesystem::path& result,
                            const std::filesystem::path& prefix,
                            std::optional<io::VectorFile> line) {
  writing([&] {
    if (line) {
      std::filesystem::path file = prefix;
      file += *line == io::VectorFile::gpkg ? "_inundation_line.gpkg" : "_inundation_line.geojson";
      if (const auto reached = io::export_inundation_line(result, file, *line)) {
        spdlog::info(
            "wrote {}: {} line{}, the highest ground reached {:.4g} m{} at ({:.2f}, {:.2f})",
            file.string(), reached->lines, reached->lines == 1 ? "" : "s",
            reached->max_ground_elevation_m,
            reached->max_runup_m
                ? fmt::format(" ({:.4g} m above the still level)", *reached->max_runup_m)
                : std::string(),
            reached->x_m, reached->y_m);
      } else {
        spdlog::info("no inundation line: the water never stopped short of dry ground");
      }
    }
    std::filesystem::path csv = prefix;
    csv += "_gauge_arrivals.csv";
    if (io::export_gauge_arrivals(result, csv)) spdlog::info("wrote {}", csv.string());
  });
}

MapOutput::MapOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain,
                     const swe::RegularGrid& grid, const RunContext& context, bool particles,
                     const std::string& depth_long_name, const std::string& title_note,
                     const std::optional<io::WriterPosition>& resume)
    : wet_depth_m_(scene.output.wet_depth_m),
      rasters_(scene.output.rasters),
      raster_cog_(scene.output.raster_cog),
      tsunami_(scene.output.tsunami),
      bed_(terrain.bed),
      bed_m_(grid_bed(terrain, grid)),
      statistics_(grid.nx * grid.ny,
                  {scene.output.wet_depth_m, scene.output.depth_thresholds_m, scene.output.land_use,
                   tsunami_ ? std::optional<maps::TsunamiLevels>(tsunami_->levels) : std::nullopt},
                  bed_m_),
      provenance_(grid.nx * grid.ny,
                  scene.output.provenance.sources ? scenario::provenance_labels(scene).size() : 0,
                  scene.output.provenance.age, scene.output.wet_depth_m) {
  const std::string started = utc_now();
  io::RunMetadata meta;
  meta.title = scene.name;
  meta.scenario_file =
      std::string("swe-mps ") + SWEMPS_VERSION + ", scenario " + context.scenario_file.string();
  // CF's history: when, and the command.
  meta.history = started + " " + context.command_line;
  meta.gravity_m_s2 = scene.numerics.gravity_m_s2;
  meta.program = std::string("swe-mps ") + SWEMPS_VERSION;
  meta.scene_json = scene.as_read_json;
  meta.command_line = context.command_line;
  meta.run_started = started;
  if (scene.output.start_time) {
    meta.start_time = *scene.output.start_time;
    meta.time_units = *scene.output.start_time_units;
  }
  if (!scene.description.empty()) meta.title += ": " + scene.description;
  if (!title_note.empty()) meta.title += " (" + title_note + ")";
  io::Layout layout{
      {grid.x0, grid.y0, grid.dx, grid.dy, grid.nx, grid.ny, terrain.crs_wkt}, particles, {}};
  if (!depth_long_name.empty()) layout.depth_long_name = depth_long_name;
  for (const auto& g : scene.output.gauges) {
    layout.gauges.push_back({g.name, g.position_m[0], g.position_m[1]});
  }
  if (scene.output.provenance.sources) layout.sources = scenario::provenance_labels(scene);
  layout.ages = scene.output.provenance.age;
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
  // Where the water came from, where the cell is wet: a film's shares and age are noise.
  std::vector<double> source_share(state.source_depth.size(), kNaN), mean_age;
  for (std::size_t k = 0; k < source_share.size(); ++k) {
    const std::size_t c = k % cells;
    if (state.depth[c] > wet_depth_m_) source_share[k] = state.source_depth[k] / state.depth[c];
  }
  if (!state.entry_time.empty()) {
    mean_age.assign(cells, kNaN);
    for (std::size_t c = 0; c < cells; ++c) {
      if (state.depth[c] > wet_depth_m_) mean_age[c] = time_s - state.entry_time[c];
    }
  }
  const io::MapFields fields{state.depth,        surface,      u,       v,
                             state.source_depth, source_share, mean_age};
  writing([&] {
    if (particles != nullptr) {
      writer_->write(time_s, *particles, fields);
    } else {
      writer_->write(time_s, fields);
    }
  });
}

void MapOutput::update_statistics(double time_s, const GriddedState& state) {
  statistics_.update(time_s, state.depth, state.u, state.v);
  if (provenance_.kept()) {
    provenance_.update(time_s, state.depth, state.source_depth, state.entry_time);
  }
}

void MapOutput::sample_series(double time_s, std::span<const io::GaugeSample> gauges,
                              const io::BalanceSample& balance) {
  writing([&] { writer_->write_series(time_s, gauges, balance); });
}

double MapOutput::bed_at(double x_m, double y_m) const {
  return bed_ ? bed_->elevation(x_m, y_m) : 0.0;
}

void MapOutput::finish() {
  writing([&] {
    writer_->write_summary(statistics_);
    writer_->write_provenance_summary(provenance_);
    writer_->write_status("complete", "");
    writer_->finish();
  });
  // The products are made from the finished file, as `swe-mps export` makes them.
  std::filesystem::path prefix = writer_->path();
  prefix.replace_extension();
  writing([&] {
    if (!rasters_.empty()) {
      const auto layout = raster_cog_ ? io::TiffLayout::cloud_optimised : io::TiffLayout::plain;
      for (const auto& file : io::export_maps(writer_->path(), rasters_, layout, prefix)) {
        spdlog::info("wrote {}", file.string());
      }
    }
    std::filesystem::path csv = prefix;
    csv += "_gauges.csv";
    if (io::export_gauges(writer_->path(), csv)) spdlog::info("wrote {}", csv.string());
  });
  if (tsunami_) {
    std::optional<io::VectorFile> line;
    if (tsunami_->inundation_line == scenario::VectorFormat::gpkg) line = io::VectorFile::gpkg;
    if (tsunami_->inundation_line == scenario::VectorFormat::geojson) {
      line = io::VectorFile::geojson;
    }
    write_tsunami_products(writer_->path(), prefix, line);
  }
}

void MapOutput::close_stopped(const std::string& status, const std::string& message) {
  writing([&] {
    writer_->write_summary(statistics_);
    writer_->write_provenance_summary(provenance_);
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
  // Only with provenance: a record without it is laid out as before.
  if (provenance_.kept()) {
    for (const auto map : provenance_.maps()) out.numbers(map);
  }
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
  for (std::size_t k = 0; k < statistics_.maps().size(); ++k) maps.push_back(in.numbers());
  try {
    statistics_.restore(samples, last_time_s, std::move(maps));
    if (provenance_.kept()) {
      std::vector<std::vector<double>> maxima;
      for (std::size_t k = 0; k < provenance_.maps().size(); ++k) maxima.push_back(in.numbers());
      provenance_.restore(std::move(maxima));
    }
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

}  // namespace swemps::cli
