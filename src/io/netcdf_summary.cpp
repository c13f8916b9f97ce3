// The whole-run summary maps of a run's file (the envelopes of maps::FloodStatistics and the
// hazard classes of their maxima), written once at the end of the run.

#include <netcdf.h>

#include <cmath>
#include <string>
#include <vector>

#include "netcdf_layout.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/maps/hazard.hpp"

namespace swemps::io {

using namespace netcdf;

namespace {

// One float map of the summary.
struct SummaryMap {
  const char* name;
  std::span<const double> values;
  const char* units;
  const char* standard_name;
  const char* long_name;
  const char* cell_methods;
  std::string comment;
};

// The classes of a map of class numbers: NaN (no data) becomes the fill value.
std::vector<unsigned char> to_stored_classes(const std::vector<double>& classes) {
  std::vector<unsigned char> out(classes.size(), kFillClass);
  for (std::size_t c = 0; c < classes.size(); ++c) {
    if (!std::isnan(classes[c])) out[c] = static_cast<unsigned char>(classes[c]);
  }
  return out;
}

// CF flags: the values and the blank-separated meanings, one word each.
struct ClassMap {
  const char* name;
  const char* long_name;
  std::vector<double> classes;  // 0 (never wet) or a class number; NaN where no data
  std::vector<unsigned char> flag_values;
  std::string flag_meanings;
  std::string comment;
};

ClassMap uk_classes(const maps::FloodStatistics& stats) {
  ClassMap m{"hazard_class_uk",
             "flood hazard rating class (Defra/Environment Agency FD2321/TR1)",
             {},
             {0},
             "not_flooded",
             ""};
  const auto rating = stats.max_hazard_rating();
  const auto rated = stats.max_hazard_class();  // 1 or more: a wet sample with a velocity
  m.classes.assign(rating.begin(), rating.end());
  for (std::size_t c = 0; c < m.classes.size(); ++c) {
    // The class of the largest rating is the largest class: the classes rise with the rating.
    if (std::isnan(rating[c])) continue;
    m.classes[c] = rated[c] >= 1.0 ? static_cast<double>(maps::uk_hazard_class(rating[c])) : 0.0;
  }
  using enum maps::UkHazardClass;
  m.flag_meanings += " low moderate significant extreme";
  m.comment = "class of max_hazard_rating: ";
  for (const auto k : {low, moderate, significant, extreme}) {
    m.flag_values.push_back(static_cast<unsigned char>(k));
    m.comment += std::to_string(static_cast<int>(k)) + " " + std::string(maps::name(k)) + "; ";
  }
  m.comment += "0 where the cell was never wet";
  return m;
}

ClassMap aidr_classes(const maps::FloodStatistics& stats) {
  ClassMap m{"hazard_class_aidr",
             "flood hazard vulnerability class H1-H6 (AIDR Guideline 7-3)",
             {},
             {0},
             "not_flooded",
             ""};
  const auto classes = stats.max_hazard_class();
  m.classes.assign(classes.begin(), classes.end());
  using enum maps::AidrHazard;
  m.flag_meanings += " H1 H2 H3 H4 H5 H6";
  m.comment =
      "the largest class over the wet samples, each sample classed by its own depth and "
      "speed: ";
  for (const auto k : {h1, h2, h3, h4, h5, h6}) {
    m.flag_values.push_back(static_cast<unsigned char>(k));
    m.comment += std::to_string(static_cast<int>(k)) + " " + std::string(maps::name(k)) + "; ";
  }
  m.comment += "0 where the cell was never wet";
  return m;
}

}  // namespace

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
  const std::string land_use(maps::name(stats.land_use()));
  std::vector<SummaryMap> summary{
      {"max_depth", stats.max_depth(), "m", "flood_water_thickness",
       "maximum water depth over the run", "time: maximum", "over all samples with data"},
      {"time_of_max_depth", stats.time_of_max_depth(), "s", nullptr,
       "simulated time at which the maximum depth was first reached", nullptr,
       wet_rule + "; fill value where never wet"},
      {"max_surface_elevation", stats.max_surface_elevation(), "m", nullptr,
       "maximum water-surface elevation (bed plus depth) over the run", "time: maximum",
       wet_rule + "; over wet samples; fill value where never wet"},
      {"max_speed", stats.max_speed(), "m s-1", nullptr,
       "maximum depth-averaged speed over the run", "time: maximum", velocity_rule},
      {"max_depth_speed", stats.max_depth_speed(), "m2 s-1", nullptr,
       "maximum of depth times speed over the run", "time: maximum", velocity_rule},
      {"max_depth_speed2", stats.max_depth_speed2(), "m3 s-2", nullptr,
       "maximum of depth times speed squared (momentum flux per unit width) over the run",
       "time: maximum", velocity_rule},
      {"max_hazard_rating", stats.max_hazard_rating(), "1", nullptr,
       "maximum flood hazard rating HR = d (v + 0.5) + DF over the run (Defra/Environment "
       "Agency FD2321/TR1)",
       "time: maximum",
       velocity_rule + "; each sample rated by its own depth and speed; debris factor for " +
           land_use + " land use"}};
  // The tsunami maps, only where the scene asked for them.
  const std::vector<double> surface_rise = stats.max_surface_rise();
  if (const auto& levels = stats.tsunami()) {
    const std::string still = exact_text(levels->still_level_m) + " m";
    summary.push_back({"max_surface_rise", surface_rise, "m", nullptr,
                       "maximum water-surface elevation above the sea's still level",
                       "time: maximum",
                       wet_rule + "; max_surface_elevation less the still level " + still +
                           "; fill value where never wet"});
    summary.push_back({"tsunami_arrival_time", stats.rise_arrival_time(), "s", nullptr,
                       "simulated time at which the water surface first rose the arrival rise "
                       "above the sea's still level",
                       nullptr,
                       wet_rule + "; first wet sample with bed plus depth above " + still + " + " +
                           exact_text(levels->arrival_rise_m) + " m; fill value where never"});
  }
  const std::vector<double>& thresholds = stats.thresholds();
  const std::string threshold_rule =
      "one map per depth_threshold; above: depth > the threshold; threshold 0 is the wet depth";
  const ClassMap classes[] = {uk_classes(stats), aidr_classes(stats)};

  def.redefine();
  // A resumed file may hold the summary the stopped run wrote; it is replaced.
  const auto find_or = [&](const char* name, auto define) {
    const int id = existing.optional_variable(name);
    return id >= 0 ? id : define();
  };
  const auto describe = [&](int id, const char* cell_methods, const std::string& comment) {
    if (cell_methods) def.text(id, "cell_methods", cell_methods);
    def.text(id, "comment",
             "from sample_count samples of the gridded fields; fill value where the cell never "
             "had data; " +
                 comment);
    def.number(id, "wet_depth_threshold_m", stats.wet_depth());
    def.integer(id, "sample_count", stats.samples());
  };
  std::vector<int> ids;
  for (const auto& s : summary) {
    ids.push_back(find_or(s.name, [&] {
      return def.static_map_var(ids_, s.name, s.units, s.standard_name, s.long_name);
    }));
    describe(ids.back(), s.cell_methods, s.comment);
    if (const auto& levels = stats.tsunami(); levels && maps::is_tsunami_map(s.name)) {
      // What the tsunami products made from the file (io/tsunami_products.hpp) measure from.
      def.number(ids.back(), "still_level_m", levels->still_level_m);
      def.number(ids.back(), "arrival_rise_m", levels->arrival_rise_m);
    }
  }
  const int threshold_dim = def.dimension("depth_threshold", thresholds.size());
  const int threshold_var = find_or("depth_threshold", [&] {
    const int id = def.variable("depth_threshold", NC_DOUBLE, threshold_dim);
    def.texts(id, {{"units", "m"},
                   {"long_name",
                    "depth a cell must exceed to count as reached (arrival) or "
                    "flooded (duration)"}});
    return id;
  });
  const int arrival = find_or("arrival_time", [&] {
    return def.threshold_map_var(ids_, threshold_dim, "arrival_time", "s",
                                 "simulated time of the first sample above the depth threshold");
  });
  describe(arrival, nullptr, threshold_rule + "; fill value where never above");
  const int duration = find_or("inundation_duration", [&] {
    return def.threshold_map_var(ids_, threshold_dim, "inundation_duration", "s",
                                 "time the cell was above the depth threshold");
  });
  describe(duration, nullptr,
           threshold_rule +
               "; a cell above it at sample k counts over (t_{k-1}, t_k], the "
               "first sample counts nothing");
  std::vector<int> class_ids;
  for (const ClassMap& m : classes) {
    class_ids.push_back(
        find_or(m.name, [&] { return def.class_map_var(ids_, m.name, m.long_name); }));
    def.bytes(class_ids.back(), "flag_values", m.flag_values);
    def.text(class_ids.back(), "flag_meanings", m.flag_meanings);
    describe(class_ids.back(), "time: maximum", m.comment);
  }
  def.end_define();

  const auto put_floats = [&](int id, const std::vector<float>& stored, const char* name,
                              std::size_t layer, bool layered) {
    const std::size_t start[3] = {layer, 0, 0};
    const std::size_t count[3] = {1, layout_.grid.ny, layout_.grid.nx};
    const int status = layered ? nc_put_vara_float(ncid_, id, start, count, stored.data())
                               : nc_put_var_float(ncid_, id, stored.data());
    check(status, std::string("write variable ") + name, partial_path_);
  };
  for (std::size_t k = 0; k < ids.size(); ++k) {
    put_floats(ids[k], to_stored_floats(summary[k].values), summary[k].name, 0, false);
  }
  check(nc_put_var_double(ncid_, threshold_var, thresholds.data()),
        "write variable depth_threshold", partial_path_);
  for (std::size_t j = 0; j < thresholds.size(); ++j) {
    put_floats(arrival, to_stored_floats(stats.arrival_time(j)), "arrival_time", j, true);
    put_floats(duration, to_stored_floats(stats.duration_above(j)), "inundation_duration", j, true);
  }
  for (std::size_t k = 0; k < class_ids.size(); ++k) {
    const std::vector<unsigned char> stored = to_stored_classes(classes[k].classes);
    check(nc_put_var_uchar(ncid_, class_ids[k], stored.data()),
          std::string("write variable ") + classes[k].name, partial_path_);
  }
  summary_written_ = true;
}

}  // namespace swemps::io
