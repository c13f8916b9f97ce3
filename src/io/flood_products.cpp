#include "swemps/io/flood_products.hpp"

#include <netcdf.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "netcdf_layout.hpp"
#include "result_reader.hpp"
#include "swemps/maps/hazard.hpp"
#include "text_file.hpp"

namespace swemps::io {

using namespace netcdf;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The names and colours of the hazard classes, light to dark as the hazard rises.
RasterBand uk_class_band() {
  using enum maps::UkHazardClass;
  RasterBand band{"flood hazard rating class (Defra/Environment Agency FD2321/TR1)", "1", {}, {}};
  for (const auto k : {low, moderate, significant, extreme}) {
    band.class_names.emplace_back(maps::name(k));
  }
  band.class_colours = {{255, 255, 178}, {254, 204, 92}, {253, 141, 60}, {227, 26, 28}};
  return band;
}

RasterBand aidr_class_band() {
  using enum maps::AidrHazard;
  RasterBand band{"flood hazard vulnerability class H1-H6 (AIDR Guideline 7-3)", "1", {}, {}};
  for (const auto k : {h1, h2, h3, h4, h5, h6}) band.class_names.emplace_back(maps::name(k));
  band.class_colours = {{255, 255, 204}, {255, 237, 160}, {254, 217, 118},
                        {253, 141, 60},  {227, 26, 28},   {128, 0, 38}};
  return band;
}

}  // namespace

std::vector<std::filesystem::path> export_maps(const std::filesystem::path& result,
                                               const std::vector<std::string>& names,
                                               TiffLayout layout,
                                               const std::filesystem::path& prefix) {
  const auto& known = exportable_maps();
  for (const auto& n : names) {
    if (std::find(known.begin(), known.end(), n) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument("'" + n +
                                  "' is not a map that can be exported (the maps: " + list + ")");
    }
  }
  const ResultReader in(result);
  in.variable("max_depth");  // every swe-mps result has its summary, even a stopped run's
  const Grid grid = in.grid();
  const std::size_t cells = grid.nx * grid.ny;
  std::map<std::string, std::string> metadata{{"TIFFTAG_SOFTWARE", in.text(NC_GLOBAL, "program")},
                                              {"source", result.filename().string()}};
  for (const char* key :
       {"title", "command_line", "run_started", "time_coverage_start", "run_status"}) {
    if (const std::string v = in.text(NC_GLOBAL, key); !v.empty()) metadata[key] = v;
  }
  std::erase_if(metadata, [](const auto& kv) { return kv.second.empty(); });

  std::vector<std::filesystem::path> written;
  const auto write = [&](const std::string& file_part, std::span<const double> values,
                         const RasterBand& band) {
    std::filesystem::path file = prefix;
    file += "_" + file_part + ".tif";
    write_geotiff(file, grid, values, band, layout, metadata);
    written.push_back(file);
  };
  // A map of several layers (one per depth threshold, or per source), each written alone as
  // <prefix>_<name>_<file part>.tif, its band described with the layer's own words.
  struct Layer {
    std::string file_part, description;
  };
  const auto write_layers = [&](const std::string& name, const std::vector<double>& values,
                                const RasterBand& band, const std::vector<Layer>& layers,
                                const std::string& kind) {
    if (values.size() != layers.size() * cells) {
      throw std::runtime_error("the result " + quoted(result) + " has " +
                               std::to_string(values.size()) + " values of " + name +
                               ", not one map per " + kind);
    }
    for (std::size_t j = 0; j < layers.size(); ++j) {
      RasterBand layer = band;
      layer.description += layers[j].description;
      write(name + "_" + layers[j].file_part,
            std::span<const double>(values).subspan(j * cells, cells), layer);
    }
  };
  for (const std::string& name : names.empty() ? known : names) {
    if (!in.has(name.c_str())) continue;  // bed_elevation of a flat scene
    const int id = in.variable(name.c_str());
    std::vector<double> values = in.values(name.c_str());
    if (name == "hazard_class_uk" || name == "hazard_class_aidr") {
      // 0, never wet, is no class: nodata in the raster, as in a GIS flood layer.
      for (double& v : values) {
        if (v == 0.0) v = kNaN;
      }
      write(name, values, name == "hazard_class_uk" ? uk_class_band() : aidr_class_band());
      continue;
    }
    const RasterBand band{in.text(id, "long_name"), in.text(id, "units"), {}, {}};
    if (values.size() == cells) {
      write(name, values, band);
      continue;
    }
    if (maps::is_source_map(name)) {
      // One map per source of the water, named by the source (docs/provenance.md).
      std::vector<Layer> sources;
      for (const std::string& source : in.strings("source_name")) {
        sources.push_back({column_name(source), ", source '" + source + "'"});
      }
      write_layers(name, values, band, sources, "source");
      continue;
    }
    std::vector<Layer> thresholds;
    for (const double t : in.values("depth_threshold")) {
      thresholds.push_back(
          {threshold_text(t) + "m", ", depth threshold " + threshold_text(t) + " m"});
    }
    write_layers(name, values, band, thresholds, "depth threshold");
  }
  return written;
}

std::string column_name(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '_' && c != '-' && c != '.') c = '_';
  }
  return out;
}

bool export_gauges(const std::filesystem::path& result, const std::filesystem::path& csv) {
  const ResultReader in(result);
  if (!in.has("gauge_name")) return false;
  const std::vector<std::string> gauges = in.strings("gauge_name");
  const std::vector<double> time = in.values("series_time");
  const std::size_t n = gauges.size();
  const char* const series[] = {"gauge_depth", "gauge_surface_elevation", "gauge_u", "gauge_v"};
  const char* const units[] = {"depth_m", "surface_elevation_m", "u_m_s", "v_m_s"};
  std::vector<std::vector<double>> columns;
  for (const char* name : series) {
    // Results of earlier versions have no surface elevation at the gauges.
    columns.push_back(in.has(name) ? in.values(name) : std::vector<double>(time.size() * n, kNaN));
    if (columns.back().size() != time.size() * n) {
      throw std::runtime_error("the result " + quoted(result) + " has " +
                               std::to_string(columns.back().size()) + " values of " + name +
                               " for " + std::to_string(time.size()) + " times and " +
                               std::to_string(n) + " gauges");
    }
  }

  // With provenance sources, each source's share of the water at each gauge (docs/provenance.md).
  std::vector<std::string> sources;
  std::vector<double> shares;
  if (in.has("gauge_source_share")) {
    sources = in.strings("source_name");
    shares = in.values("gauge_source_share");
    if (shares.size() != time.size() * n * sources.size()) {
      throw std::runtime_error(
          "the result " + quoted(result) + " has " + std::to_string(shares.size()) +
          " values of gauge_source_share for " + std::to_string(time.size()) + " times, " +
          std::to_string(n) + " gauges and " + std::to_string(sources.size()) + " sources");
    }
  }
  const std::size_t s = sources.size();

  std::string text = "time_s";
  for (const auto& g : gauges) {
    for (const char* unit : units) {
      // Appended piecewise: `"," + string` trips a false -Wrestrict warning in GCC 12.
      text += ',';
      text += column_name(g);
      text += '_';
      text += unit;
    }
    for (const auto& source : sources) {
      text += ',';
      text += column_name(g);
      text += "_share_";
      text += column_name(source);
    }
  }
  text += '\n';
  for (std::size_t t = 0; t < time.size(); ++t) {
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%.12g", time[t]);
    text += stamp;
    for (std::size_t g = 0; g < n; ++g) {
      for (const auto& column : columns) text::append_cell(text, column[t * n + g]);
      for (std::size_t k = 0; k < s; ++k) text::append_cell(text, shares[(t * n + g) * s + k]);
    }
    text += '\n';
  }
  std::filesystem::path partial = csv;
  partial += ".partial";
  text::write_then_rename(csv, partial, text);
  return true;
}

}  // namespace swemps::io
