// The files of an ensemble: each member's maximum depth read from its result, the products of
// ensemble::combine written as CF netCDF and as GeoTIFFs.

#include "swemps/io/ensemble_products.hpp"

#include <netcdf.h>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <system_error>

#include "netcdf_layout.hpp"
#include "result_reader.hpp"

namespace swemps::io {

using namespace netcdf;

MemberResult read_member_result(const std::filesystem::path& result) {
  const ResultReader in(result);
  MemberResult m;
  m.grid = in.grid();
  m.max_depth = in.values("max_depth");
  if (m.max_depth.size() != m.grid.nx * m.grid.ny) {
    throw std::runtime_error("the result " + quoted(result) + " has " +
                             std::to_string(m.max_depth.size()) + " values of max_depth for " +
                             std::to_string(m.grid.nx * m.grid.ny) + " cells");
  }
  m.wet_depth_m = in.number(in.variable("max_depth"), "wet_depth_threshold_m");
  m.final_volume_error = std::numeric_limits<double>::quiet_NaN();
  if (in.has("volume_error")) {
    const std::vector<double> errors = in.values("volume_error");
    if (!errors.empty()) m.final_volume_error = errors.back();
  }
  return m;
}

bool same_grid(const Grid& a, const Grid& b) {
  return a.nx == b.nx && a.ny == b.ny && a.x0 == b.x0 && a.y0 == b.y0 && a.dx == b.dx &&
         a.dy == b.dy && a.crs_wkt == b.crs_wkt;
}

namespace {

std::string member_list(const std::vector<std::size_t>& members) {
  std::string text;
  for (const std::size_t m : members) {
    if (!text.empty()) text += ' ';
    text += std::to_string(m);
  }
  return text;
}

std::string combined_text(const EnsembleSource& source) {
  return "combined from " + std::to_string(source.members_used.size()) + " of the ensemble's " +
         std::to_string(source.members_total) + " members";
}

}  // namespace

void write_ensemble_netcdf(const std::filesystem::path& path, const Grid& grid,
                           const ensemble::Products& products, const EnsembleSource& source) {
  if (grid.nx == 0 || grid.ny == 0) {
    throw std::invalid_argument("write_ensemble_netcdf: empty grid for " + quoted(path));
  }
  std::filesystem::path partial = path;
  partial += ".partial";
  const int ncid = create_netcdf4(partial);
  try {
    const Definer def{ncid, partial, grid};
    def.texts(NC_GLOBAL, {{"Conventions", "CF-1.8"}, {"references", "swe-mps shallow-water MPS"}});
    def.text(NC_GLOBAL, "title", source.title);
    def.text(NC_GLOBAL, "source", source.ensemble_file);
    def.text(NC_GLOBAL, "program", source.program);
    def.text(NC_GLOBAL, "comment",
             "products of an ensemble of runs, " + combined_text(source) +
                 ", each member's whole-run maximum depth (max_depth of its result); a cell "
                 "without data in a member counts as dry there");
    def.integer(NC_GLOBAL, "ensemble_members", source.members_total);
    def.integer(NC_GLOBAL, "ensemble_members_combined", source.members_used.size());
    def.text(NC_GLOBAL, "ensemble_members_combined_list", member_list(source.members_used));

    const Definer::GridIds grid_ids = def.define_grid();
    detail::NetcdfIds ids;
    ids.y_dim = grid_ids.y_dim;
    ids.x_dim = grid_ids.x_dim;
    const int threshold_dim = def.dimension("depth_threshold", products.thresholds_m.size());
    const int threshold_var = def.variable("depth_threshold", NC_DOUBLE, threshold_dim);
    def.texts(
        threshold_var,
        {{"units", "m"}, {"long_name", "depth a member's maximum depth must exceed to count"}});
    const int count =
        def.threshold_map_var(ids, threshold_dim, "exceedance_count", "1",
                              "number of members whose maximum depth exceeds the depth threshold");
    const int probability = def.threshold_map_var(
        ids, threshold_dim, "exceedance_probability", "1",
        "fraction of the members whose maximum depth exceeds the depth threshold");
    const int mean = def.static_map_var(ids, "mean_max_depth", "m", nullptr,
                                        "mean over the members of the maximum water depth");
    const int envelope = def.static_map_var(ids, "max_depth_envelope", "m", nullptr,
                                            "largest maximum water depth of any member");
    for (const int id : {count, probability, mean, envelope}) {
      def.text(id, "comment", combined_text(source) + "; fill value where no member had data");
    }
    def.text(count, "cell_methods", "realization: sum");
    def.text(mean, "cell_methods", "time: maximum realization: mean");
    def.text(envelope, "cell_methods", "time: maximum realization: maximum");
    def.end_define();

    def.write_grid(grid_ids);
    check(nc_put_var_double(ncid, threshold_var, products.thresholds_m.data()),
          "write variable depth_threshold", partial);
    const auto put = [&](int id, const std::vector<double>& values, const char* name,
                         std::size_t layer, bool layered) {
      const std::vector<float> stored = to_stored_floats(values);
      const std::size_t start[3] = {layer, 0, 0};
      const std::size_t counts[3] = {1, grid.ny, grid.nx};
      check(layered ? nc_put_vara_float(ncid, id, start, counts, stored.data())
                    : nc_put_var_float(ncid, id, stored.data()),
            std::string("write variable ") + name, partial);
    };
    for (std::size_t j = 0; j < products.thresholds_m.size(); ++j) {
      put(count, products.exceedance_count[j], "exceedance_count", j, true);
      put(probability, products.exceedance_probability[j], "exceedance_probability", j, true);
    }
    put(mean, products.mean_max_depth, "mean_max_depth", 0, false);
    put(envelope, products.max_depth_envelope, "max_depth_envelope", 0, false);
  } catch (...) {
    nc_close(ncid);
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw;
  }
  check(nc_close(ncid), "close the file", partial);
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    throw std::runtime_error("cannot rename " + quoted(partial) + " to " + quoted(path) + ": " +
                             ec.message());
  }
}

std::vector<std::filesystem::path> write_ensemble_rasters(const std::filesystem::path& prefix,
                                                          const Grid& grid,
                                                          const ensemble::Products& products,
                                                          const EnsembleSource& source,
                                                          TiffLayout layout) {
  // No date: the same members make the same files.
  const std::map<std::string, std::string> metadata{{"TIFFTAG_SOFTWARE", source.program},
                                                    {"title", source.title},
                                                    {"source", source.ensemble_file},
                                                    {"members", combined_text(source)}};
  std::vector<std::filesystem::path> written;
  const auto write = [&](const std::string& part, const std::vector<double>& values,
                         const std::string& description, const char* units) {
    std::filesystem::path file = prefix;
    file += "_" + part + ".tif";
    write_geotiff(file, grid, values, RasterBand{description, units, {}, {}}, layout, metadata);
    written.push_back(file);
  };
  for (std::size_t j = 0; j < products.thresholds_m.size(); ++j) {
    const std::string t = threshold_text(products.thresholds_m[j]);
    write("exceedance_probability_" + t + "m", products.exceedance_probability[j],
          "fraction of the members whose maximum depth exceeds " + t + " m", "1");
    write("exceedance_count_" + t + "m", products.exceedance_count[j],
          "number of members whose maximum depth exceeds " + t + " m", "1");
  }
  write("mean_max_depth", products.mean_max_depth,
        "mean over the members of the maximum water depth", "m");
  write("max_depth_envelope", products.max_depth_envelope,
        "largest maximum water depth of any member", "m");
  return written;
}

}  // namespace swemps::io
