#include "swemps/ns/boundary_pressure.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace swemps::ns {

void build_boundary_extrapolation(const neighbors::NeighborList& pairs,
                                  std::span<const double> pair_weight, std::size_t fluid_count,
                                  std::size_t particle_count, std::span<const double> vertical,
                                  double rho_g, BoundaryExtrapolation& out) {
  if (pair_weight.size() != pairs.index.size() || pairs.row_count() < fluid_count ||
      vertical.size() < particle_count || particle_count < fluid_count) {
    throw std::invalid_argument("boundary pressure: inputs do not match the neighbour list");
  }
  const std::size_t boundary_count = particle_count - fluid_count;
  out.fluid_count = fluid_count;
  out.offsets.assign(boundary_count + 1, 0);
  // Two passes over the fluid rows, ascending k, so each boundary particle's list is sorted
  // and the result does not depend on the thread count that built the neighbour list.
  for (std::size_t k = 0; k < fluid_count; ++k) {
    const std::size_t first = pairs.offsets[k];
    const auto row = pairs.row(k);
    for (std::size_t m = 0; m < row.size(); ++m) {
      if (row[m] >= fluid_count && pair_weight[first + m] > 0.0) {
        ++out.offsets[row[m] - fluid_count + 1];
      }
    }
  }
  for (std::size_t b = 0; b < boundary_count; ++b) out.offsets[b + 1] += out.offsets[b];
  out.fluid.resize(out.offsets.back());
  out.alpha.resize(out.offsets.back());
  std::vector<std::size_t> cursor(out.offsets.begin(), out.offsets.end() - 1);
  for (std::size_t k = 0; k < fluid_count; ++k) {
    const std::size_t first = pairs.offsets[k];
    const auto row = pairs.row(k);
    for (std::size_t m = 0; m < row.size(); ++m) {
      const double w = pair_weight[first + m];
      if (row[m] < fluid_count || !(w > 0.0)) continue;
      const std::size_t slot = cursor[row[m] - fluid_count]++;
      out.fluid[slot] = static_cast<std::uint32_t>(k);
      out.alpha[slot] = w;
    }
  }
  out.constant.assign(boundary_count, 0.0);
  for (std::size_t b = 0; b < boundary_count; ++b) {
    double total = 0.0;
    for (std::size_t s = out.offsets[b]; s < out.offsets[b + 1]; ++s) total += out.alpha[s];
    if (!(total > 0.0)) continue;
    const double height = vertical[fluid_count + b];
    double lift = 0.0;
    for (std::size_t s = out.offsets[b]; s < out.offsets[b + 1]; ++s) {
      out.alpha[s] /= total;
      lift += out.alpha[s] * (vertical[out.fluid[s]] - height);
    }
    out.constant[b] = rho_g * lift;
  }
}

void assemble_poisson_extrapolated(const neighbors::NeighborList& pairs,
                                   std::span<const double> pair_weight,
                                   std::span<const char> unknown, std::span<const double> source,
                                   const BoundaryExtrapolation& boundary, double laplacian_factor,
                                   PoissonSystem& out, std::span<const double> coefficient) {
  const std::size_t fluid_count = boundary.fluid_count;
  if (pair_weight.size() != pairs.index.size() ||
      (!coefficient.empty() && coefficient.size() != pairs.index.size()) || unknown.size() < fluid_count ||
      source.size() < fluid_count || pairs.row_count() < fluid_count) {
    throw std::invalid_argument("poisson: inputs do not match the neighbour list");
  }
  if (!(laplacian_factor > 0.0)) throw std::invalid_argument("poisson: laplacian factor <= 0");
  const std::vector<std::int32_t> unknown_of_particle = number_unknowns(unknown, fluid_count, out);
  const auto n = static_cast<int>(out.particle_of_unknown.size());
  const double to_system = -1.0 / laplacian_factor;
  out.rhs.resize(n);

  // Each row is accumulated column by column in a dense scratch row (a fluid neighbour k is
  // reached directly and through every boundary particle the two share: in 3D hundreds of
  // products fall on a few dozen columns), then its columns are sorted and appended in
  // compressed form. Every entry sums its products in the order they are reached, the
  // diagonal's own term last.
  std::vector<int> row_start(static_cast<std::size_t>(n) + 1, 0);
  std::vector<std::pair<int, double>> entries;
  std::vector<double> accumulated(static_cast<std::size_t>(n), 0.0);
  std::vector<int> last_row(static_cast<std::size_t>(n), -1);
  std::vector<int> columns;
  for (int r = 0; r < n; ++r) {
    const std::size_t i = out.particle_of_unknown[static_cast<std::size_t>(r)];
    columns.clear();
    const auto add = [&](std::int32_t column, double value) {
      const auto c = static_cast<std::size_t>(column);
      if (last_row[c] != r) {
        last_row[c] = r;
        accumulated[c] = value;
        columns.push_back(column);
      } else {
        accumulated[c] += value;
      }
    };
    double diagonal = 0.0, lifted = 0.0;
    const std::size_t first = pairs.offsets[i];
    const auto neighbours = pairs.row(i);
    for (std::size_t m = 0; m < neighbours.size(); ++m) {
      const std::uint32_t j = neighbours[m];
      // A pair counts where its kernel weight is positive (a polynomial kernel rounds to a
      // tiny negative value at its cut-off); its coefficient may be negative.
      if (!(pair_weight[first + m] > 0.0)) continue;
      const double w = coefficient.empty() ? pair_weight[first + m] : coefficient[first + m];
      diagonal += w;
      if (j < fluid_count) {
        if (unknown_of_particle[j] >= 0) add(unknown_of_particle[j], -w);
        continue;
      }
      const std::size_t b = j - fluid_count;
      lifted += w * boundary.constant[b];
      for (std::size_t s = boundary.offsets[b]; s < boundary.offsets[b + 1]; ++s) {
        const std::int32_t column = unknown_of_particle[boundary.fluid[s]];
        if (column >= 0) add(column, -w * boundary.alpha[s]);
      }
    }
    add(r, diagonal);
    std::sort(columns.begin(), columns.end());
    for (const int column : columns) {
      entries.emplace_back(column, accumulated[static_cast<std::size_t>(column)]);
    }
    row_start[static_cast<std::size_t>(r) + 1] = static_cast<int>(entries.size());
    out.rhs[r] = to_system * source[i] + lifted;
  }
  auto& a = out.matrix;
  a.resize(n, n);
  a.resizeNonZeros(static_cast<Eigen::Index>(entries.size()));
  std::copy(row_start.begin(), row_start.end(), a.outerIndexPtr());
  for (std::size_t s = 0; s < entries.size(); ++s) {
    a.innerIndexPtr()[s] = entries[s].first;
    a.valuePtr()[s] = entries[s].second;
  }
}

void extrapolate_boundary_pressure(const BoundaryExtrapolation& boundary,
                                   std::span<double> pressure) {
  const std::size_t boundary_count = boundary.constant.size();
  if (pressure.size() < boundary.fluid_count + boundary_count) {
    throw std::invalid_argument("boundary pressure: pressure field too short");
  }
  for (std::size_t b = 0; b < boundary_count; ++b) {
    double value = 0.0;
    for (std::size_t s = boundary.offsets[b]; s < boundary.offsets[b + 1]; ++s) {
      value += boundary.alpha[s] * pressure[boundary.fluid[s]];
    }
    pressure[boundary.fluid_count + b] =
        boundary.offsets[b + 1] > boundary.offsets[b] ? value + boundary.constant[b] : 0.0;
  }
}

}  // namespace swemps::ns
