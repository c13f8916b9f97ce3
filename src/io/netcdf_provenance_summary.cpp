// The whole-run maxima of the provenance maps in a run's file (docs/provenance.md), written
// with the summary maps at the end of the run.

#include <netcdf.h>

#include <string>
#include <vector>

#include "netcdf_layout.hpp"
#include "swemps/io/netcdf_writer.hpp"

namespace swemps::io {

using namespace netcdf;

void NetcdfWriter::write_provenance_summary(const maps::ProvenanceMaxima& maxima) {
  require_open("write_provenance_summary");
  const std::size_t cells = layout_.grid.nx * layout_.grid.ny;
  const std::size_t sources = layout_.sources.size();
  if (maxima.sources() != sources || maxima.ages() != layout_.ages ||
      maxima.max_source_depth().size() != sources * cells) {
    throw std::invalid_argument("NetcdfWriter::write_provenance_summary: maxima for " +
                                quoted(path_) + " of another layout");
  }
  const Definer def{ncid_, partial_path_, layout_.grid};
  const Resumer existing{ncid_, partial_path_};
  // A resumed file may hold the maxima the stopped run wrote; they are replaced.
  const auto find_or = [&](const char* name, auto define) {
    const int id = existing.optional_variable(name);
    return id >= 0 ? id : define();
  };
  struct Maximum {
    const char* name;
    std::span<const double> values;
    const char* units;
    const char* long_name;
    bool per_source;
    int id = -1;
  };
  std::vector<Maximum> written;
  if (sources > 0) {
    written.push_back({"max_source_depth", maxima.max_source_depth(), "m",
                       "maximum depth of the water that came from each source over the run", true});
    written.push_back({"max_source_share", maxima.max_source_share(), "1",
                       "largest share of the cell's water that came from each source over the "
                       "run, over the samples where the cell was wet; fill value where never wet",
                       true});
  }
  if (layout_.ages) {
    written.push_back({"max_mean_age", maxima.max_mean_age(), "s",
                       "largest volume-weighted mean age of the cell's water over the run, over "
                       "the samples where the cell was wet; fill value where never wet",
                       false});
  }
  if (written.empty()) return;
  def.redefine();
  int source_dim = -1;
  if (sources > 0) {
    check(nc_inq_dimid(ncid_, "source", &source_dim), "find dimension source", partial_path_);
  }
  for (Maximum& m : written) {
    m.id = find_or(m.name, [&] {
      return m.per_source ? def.threshold_map_var(ids_, source_dim, m.name, m.units, m.long_name)
                          : def.static_map_var(ids_, m.name, m.units, nullptr, m.long_name);
    });
    def.text(m.id, "cell_methods", "time: maximum");
    if (m.per_source) def.text(m.id, "coordinates", "source_name");
  }
  def.end_define();
  for (const Maximum& m : written) {
    const std::vector<float> stored = to_stored_floats(m.values);
    check(nc_put_var_float(ncid_, m.id, stored.data()), std::string("write variable ") + m.name,
          partial_path_);
  }
}

}  // namespace swemps::io
