#include "swemps/neighbors/row_repair.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace swemps::neighbors {

template <int Dim>
std::vector<std::uint32_t> repair_rows(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                                       std::span<const double> radii, std::size_t target_count,
                                       std::span<const std::uint32_t> changed, NeighborList& list) {
  const std::size_t points = coords[0].size();
  const std::size_t old_rows = list.row_count();
  if (radii.size() != points || cells.point_count() != points || target_count > points ||
      old_rows > target_count) {
    throw std::invalid_argument("repair_rows: the list, points, radii and cells do not agree");
  }
  if (!std::is_sorted(changed.begin(), changed.end()) ||
      std::adjacent_find(changed.begin(), changed.end()) != changed.end() ||
      (!changed.empty() && changed.back() >= points)) {
    throw std::invalid_argument("repair_rows: changed points must be ascending, distinct, listed");
  }
  const auto is_changed = [&](std::uint32_t j) {
    return std::binary_search(changed.begin(), changed.end(), j);
  };
  for (std::size_t i = old_rows; i < target_count; ++i) {
    if (!is_changed(static_cast<std::uint32_t>(i)))
      throw std::invalid_argument("repair_rows: a new target is not changed");
  }
  if (changed.empty()) return {};

  // Every pair (c, j) with c changed: the same squared distance, and the same comparison with
  // the larger radius, as the builder makes, so that the rows are those it would write.
  double largest = 0.0;
  for (const double r : radii) largest = std::max(largest, r);
  const auto order = cells.order();
  std::array<const double*, Dim> ordered{};
  for (int d = 0; d < Dim; ++d) ordered[d] = cells.cell_ordered(d).data();
  std::vector<std::vector<std::uint32_t>> found(changed.size());
  for (std::size_t m = 0; m < changed.size(); ++m) {
    const std::uint32_t c = changed[m];
    std::array<double, Dim> p{};
    for (int d = 0; d < Dim; ++d) p[d] = coords[d][c];
    const double rc2 = radii[c] * radii[c];
    const auto reach = cells.reach_for(std::max(radii[c], largest));
    cells.for_each_candidate_range(p, reach, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t k = begin; k < end; ++k) {
        double r2 = 0.0;
        for (int d = 0; d < Dim; ++d) {
          const double delta = ordered[d][k] - p[d];
          r2 += delta * delta;
        }
        const std::uint32_t j = order[k];
        if (j != c && r2 < std::max(rc2, radii[j] * radii[j])) found[m].push_back(j);
      }
    });
    std::sort(found[m].begin(), found[m].end());
  }

  // The rows to rewrite: the changed targets', and every target's that held a changed point or
  // now holds one. Rows are symmetric among targets, so a changed target's old row names those
  // that held it; which rows held a changed point that is no target (a ghost) only a pass over
  // every row tells.
  std::vector<std::uint32_t> targets;
  bool changed_beyond_targets = false;
  for (std::size_t m = 0; m < changed.size(); ++m) {
    const std::uint32_t c = changed[m];
    if (c < target_count) targets.push_back(c);
    changed_beyond_targets = changed_beyond_targets || c >= target_count;
    if (c < old_rows)
      for (const std::uint32_t j : list.row(c))
        if (j < target_count) targets.push_back(j);
    for (const std::uint32_t j : found[m])
      if (j < target_count) targets.push_back(j);
  }
  if (changed_beyond_targets) {
    for (std::uint32_t i = 0; i < old_rows; ++i) {
      const auto row = list.row(i);
      if (std::any_of(row.begin(), row.end(), is_changed)) targets.push_back(i);
    }
  }
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());

  // Their new contents, before any row moves: a changed target's row is what was found for it;
  // another keeps its unchanged points and gains, in order, the changed ones that reach it.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> gained;  // (target, changed point)
  for (std::size_t m = 0; m < changed.size(); ++m)
    for (const std::uint32_t j : found[m])
      if (j < target_count && !is_changed(j)) gained.emplace_back(j, changed[m]);
  std::sort(gained.begin(), gained.end());
  std::vector<std::vector<std::uint32_t>> rows(targets.size());
  std::size_t next_gain = 0;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const std::uint32_t i = targets[t];
    auto& row = rows[t];
    if (is_changed(i)) {
      row = found[static_cast<std::size_t>(std::lower_bound(changed.begin(), changed.end(), i) -
                                           changed.begin())];
      continue;
    }
    for (const std::uint32_t j : list.row(i))
      if (!is_changed(j)) row.push_back(j);
    const std::size_t kept = row.size();
    while (next_gain < gained.size() && gained[next_gain].first < i) ++next_gain;
    for (; next_gain < gained.size() && gained[next_gain].first == i; ++next_gain)
      row.push_back(gained[next_gain].second);
    std::inplace_merge(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(kept), row.end());
  }

  // The other rows move, in place, by the lengths the rewritten rows before them gained or
  // lost: those moving towards the front from the front, those moving back from the back, so
  // that no row is overwritten before it has moved (a copy of the list would double its
  // memory for a few rows).
  const auto old_length = [&](std::size_t i) -> std::size_t {
    return i < old_rows ? list.offsets[i + 1] - list.offsets[i] : 0;
  };
  std::size_t old_total = list.index.size(), new_total = old_total;
  for (std::size_t t = 0; t < targets.size(); ++t)
    new_total = new_total + rows[t].size() - old_length(targets[t]);
  list.index.resize(std::max(old_total, new_total));
  const auto move_row = [&](std::size_t i, std::size_t to) {
    const std::size_t from = list.offsets[i], length = old_length(i);
    if (length > 0 && from != to)
      std::memmove(list.index.data() + to, list.index.data() + from,
                   length * sizeof(std::uint32_t));
  };
  std::vector<std::size_t> new_start(targets.size());
  {
    // Forward: the new start of each row, moving those that go towards the front.
    std::size_t at = 0, t = 0;
    for (std::size_t i = 0; i < target_count; ++i) {
      if (t < targets.size() && targets[t] == i) {
        new_start[t] = at;
        at += rows[t].size();
        ++t;
        continue;
      }
      if (at <= list.offsets[i]) move_row(i, at);
      at += old_length(i);
    }
    // Backward: those that go towards the back.
    std::size_t end = at;
    t = targets.size();
    for (std::size_t i = target_count; i-- > 0;) {
      if (t > 0 && targets[t - 1] == i) {
        end -= rows[--t].size();
        continue;
      }
      end -= old_length(i);
      if (end > list.offsets[i]) move_row(i, end);
    }
  }
  for (std::size_t t = 0; t < targets.size(); ++t)
    std::copy(rows[t].begin(), rows[t].end(),
              list.index.begin() + static_cast<std::ptrdiff_t>(new_start[t]));
  list.index.resize(new_total);
  // The offsets last, in one pass from the front: the moves read the old ones, and a row's old
  // length reads its own and the next offset, which the pass has not yet overwritten (a new
  // row has none to read).
  list.offsets.resize(target_count + 1);
  std::uint32_t at = 0;
  for (std::size_t i = 0, t = 0; i < target_count; ++i) {
    const bool rewritten = t < targets.size() && targets[t] == i;
    const std::size_t length = rewritten ? rows[t++].size() : old_length(i);
    list.offsets[i] = at;
    at += static_cast<std::uint32_t>(length);
  }
  list.offsets[target_count] = at;
  return targets;
}

template std::vector<std::uint32_t> repair_rows<2>(const CellList<2>&, const Coordinates<2>&,
                                                   std::span<const double>, std::size_t,
                                                   std::span<const std::uint32_t>, NeighborList&);
template std::vector<std::uint32_t> repair_rows<3>(const CellList<3>&, const Coordinates<3>&,
                                                   std::span<const double>, std::size_t,
                                                   std::span<const std::uint32_t>, NeighborList&);

}  // namespace swemps::neighbors
