#include "swemps/splitting/particle_merging.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace swemps::splitting {

ParticleMerging::ParticleMerging(MergingSettings settings,
                                 std::vector<boundaries::WallSegment> walls)
    : settings_(settings), walls_(std::move(walls)) {}

bool ParticleMerging::merge_allowed(const particles::SweParticles& p, std::size_t i,
                                    std::size_t j) const {
  return p.area[i] + p.area[j] <
         settings_.area_ratio_threshold * (p.initial_area[i] + p.initial_area[j]);
}

std::size_t ParticleMerging::nearest_partner(const particles::SweParticles& p,
                                             std::size_t i) const {
  std::size_t best = i;
  double best_r2 = std::numeric_limits<double>::infinity();
  cells_.for_each_candidate({p.x[i], p.y[i]}, [&](std::uint32_t j) {
    if (j == i || taken_[j] || !(p.smoothing_length[j] > 0.0)) return;
    const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i];
    const double r2 = dx * dx + dy * dy;
    const double reach = std::max(p.smoothing_length[i], p.smoothing_length[j]);
    if (r2 > reach * reach) return;
    // Ties go to the lower index, so that the pairs never depend on the cells' order.
    if (r2 > best_r2 || (r2 == best_r2 && j > best)) return;
    if (!merge_allowed(p, i, j) || walls_.crosses_any({p.x[i], p.y[i]}, {p.x[j], p.y[j]})) return;
    best = j;
    best_r2 = r2;
  });
  return best;
}

void ParticleMerging::apply(swe::StepContext& context) {
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();
  candidates_.clear();
  double widest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    widest = std::max(widest, p.smoothing_length[i]);
    // A particle not yet summed (radius 0: just let in) has no area to judge it by.
    if (!(p.smoothing_length[i] > 0.0)) continue;
    if (p.area[i] < settings_.area_ratio_threshold * p.initial_area[i]) {
      candidates_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (candidates_.empty()) return;
  cells_.build({std::span<const double>(p.x.data(), n), std::span<const double>(p.y.data(), n)},
               widest);
  taken_.assign(n, 0);
  merged_away_.assign(n, 0);
  std::size_t merged_now = 0;
  // Greedy, in index order: the pairs are the same on any number of threads.
  for (const std::uint32_t i : candidates_) {
    if (taken_[i]) continue;
    const std::size_t j = nearest_partner(p, i);
    if (j == i) continue;
    taken_[i] = taken_[j] = 1;
    // The lower index keeps the pair; the other is removed below.
    const std::size_t a = std::min<std::size_t>(i, j), b = std::max<std::size_t>(i, j);
    const double va = p.volume[a], vb = p.volume[b];
    const double volume = va + vb;
    const auto weighted = [&](const std::vector<double>& f) {
      return (va * f[a] + vb * f[b]) / volume;
    };
    p.mix_provenance(a, va, b, vb);
    p.hand_over_pathline(b, a);
    p.x[a] = weighted(p.x);
    p.y[a] = weighted(p.y);
    p.u[a] = weighted(p.u);
    p.v[a] = weighted(p.v);
    p.bed[a] = weighted(p.bed);
    p.initial_area[a] = 0.5 * (p.initial_area[a] + p.initial_area[b]);
    p.area[a] += p.area[b];
    p.depth[a] = volume / p.area[a];
    p.smoothing_length[a] = std::hypot(p.smoothing_length[a], p.smoothing_length[b]);
    p.volume[a] = volume;
    merged_away_[b] = 1;
    ++merged_now;
  }
  if (merged_now == 0) return;
  p.remove(merged_away_);
  merges_ += merged_now;
}

std::string ParticleMerging::report() const { return std::to_string(merges_) + " merges"; }

void ParticleMerging::save_state(swe::StateWriter& out) const { out.count(merges_); }

void ParticleMerging::restore_state(swe::StateReader& in) { merges_ = in.count(); }

}  // namespace swemps::splitting
