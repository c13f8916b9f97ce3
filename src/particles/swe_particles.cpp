#include "swemps/particles/swe_particles.hpp"

#include <numeric>
#include <stdexcept>
#include <string>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::particles {

namespace {

// Gathers `field[order[k]]` into `scratch`, then swaps it in. The scratch vector is passed
// by reference so one allocation serves every field of a reorder.
template <typename T>
void permute(std::vector<T>& field, std::span<const std::uint32_t> order, std::vector<T>& scratch) {
  scratch.resize(order.size());
  parallel_for(order.size(), [&](std::size_t k) { scratch[k] = field[order[k]]; });
  field.swap(scratch);
}

// Stable in-place compaction: keeps the entries whose flag is zero, in order.
template <typename T>
void compact(std::vector<T>& field, std::span<const std::uint8_t> flagged) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < flagged.size(); ++i) {
    if (!flagged[i]) field[kept++] = field[i];
  }
  field.resize(kept);
}

// A wrong permutation would silently duplicate some particles and lose others, which
// breaks volume conservation in ways that are hard to trace back; checking is O(n).
void require_permutation(std::span<const std::uint32_t> order) {
  std::vector<std::uint8_t> seen(order.size(), 0);
  for (const std::uint32_t idx : order) {
    if (idx >= order.size() || seen[idx]) {
      throw std::invalid_argument("SweParticles::reorder: order is not a permutation (index " +
                                  std::to_string(idx) + ")");
    }
    seen[idx] = 1;
  }
}

}  // namespace

void SweParticles::add_fluid(double px, double py, double pu, double pv, double vol, double h,
                             double a0, double zb, Origin origin) {
  // Ghosts sit behind the fluid block; appending fluid behind them would break the
  // "fluid first" layout every loop relies on.
  if (ghost_count() != 0) {
    throw std::logic_error("SweParticles::add_fluid: ghosts must be dropped first");
  }
  const auto own = static_cast<std::uint32_t>(size());
  x.push_back(px);
  y.push_back(py);
  u.push_back(pu);
  v.push_back(pv);
  volume.push_back(vol);
  depth.push_back(h);
  area.push_back(a0);
  initial_area.push_back(a0);
  bed.push_back(zb);
  number_density.push_back(0.0);
  smoothing_length.push_back(0.0);
  omega.push_back(1.0);
  source.push_back(own);
  if (label_count_ > 0) {
    if (origin.label >= label_count_) {
      throw std::out_of_range("SweParticles::add_fluid: label " + std::to_string(origin.label) +
                              " of " + std::to_string(label_count_));
    }
    label_share.resize(label_share.size() + label_count_, 0.0);
    label_share[fluid_count_ * label_count_ + origin.label] = 1.0;
  }
  if (tracks_ages_) entry_time.push_back(origin.entry_time_s);
  if (tracks_pathlines_) pathline.push_back(kNoPathline);
  ++fluid_count_;
  mirror_end_ = fluid_count_;
}

void SweParticles::add_ghost(std::uint32_t from, double px, double py, double pu, double pv) {
  if (from >= fluid_count_) {
    throw std::out_of_range("SweParticles::add_ghost: source " + std::to_string(from) +
                            " is not a fluid particle");
  }
  x.push_back(px);
  y.push_back(py);
  u.push_back(pu);
  v.push_back(pv);
  volume.push_back(volume[from]);
  depth.push_back(depth[from]);
  area.push_back(area[from]);
  initial_area.push_back(initial_area[from]);
  bed.push_back(bed[from]);
  number_density.push_back(number_density[from]);
  smoothing_length.push_back(smoothing_length[from]);
  omega.push_back(omega[from]);
  source.push_back(from);
  if (!mirrors_closed_) mirror_end_ = size();
}

void SweParticles::drop_ghosts() {
  resize(fluid_count_);
  mirror_end_ = fluid_count_;
  mirrors_closed_ = false;
}

void SweParticles::resize(std::size_t n) {
  x.resize(n);
  y.resize(n);
  u.resize(n);
  v.resize(n);
  volume.resize(n);
  depth.resize(n);
  area.resize(n);
  initial_area.resize(n);
  bed.resize(n);
  number_density.resize(n);
  smoothing_length.resize(n);
  omega.resize(n);
  source.resize(n);
}

void SweParticles::reorder(std::span<const std::uint32_t> order) {
  if (ghost_count() != 0) {
    throw std::logic_error("SweParticles::reorder: ghosts must be dropped first");
  }
  if (order.size() != fluid_count_) {
    throw std::logic_error("SweParticles::reorder: order has " + std::to_string(order.size()) +
                           " entries for " + std::to_string(fluid_count_) + " particles");
  }
  require_permutation(order);

  std::vector<double> scratch;
  scratch.reserve(order.size());
  for (std::vector<double>* field :
       {&x, &y, &u, &v, &volume, &depth, &area, &initial_area, &bed, &number_density,
        &smoothing_length, &omega}) {
    permute(*field, order, scratch);
  }
  if (tracks_ages_) permute(entry_time, order, scratch);
  if (tracks_pathlines_) {
    std::vector<std::int32_t> indices;
    permute(pathline, order, indices);
  }
  if (label_count_ > 0) {
    const std::size_t labels = label_count_;
    scratch.resize(label_share.size());
    parallel_for(order.size(), [&](std::size_t k) {
      for (std::size_t l = 0; l < labels; ++l) {
        scratch[k * labels + l] = label_share[order[k] * labels + l];
      }
    });
    label_share.swap(scratch);
  }
  // Fluid particles are their own source, so the permuted field is simply 0..n-1.
  std::iota(source.begin(), source.end(), std::uint32_t{0});
}

void SweParticles::remove(std::span<const std::uint8_t> flagged) {
  if (ghost_count() != 0) {
    throw std::logic_error("SweParticles::remove: ghosts must be dropped first");
  }
  if (flagged.size() != fluid_count_) {
    throw std::logic_error("SweParticles::remove: " + std::to_string(flagged.size()) +
                           " flags for " + std::to_string(fluid_count_) + " particles");
  }
  if (tracks_pathlines_) {
    // Where each pathline's particle was when it went, before the positions are compacted.
    for (std::size_t i = 0; i < flagged.size(); ++i) {
      if (flagged[i] && pathline[i] != kNoPathline) {
        pathline_ends.push_back({pathline[i], x[i], y[i], PathlineEnd::Cause::left});
      }
    }
  }
  for (std::vector<double>* field :
       {&x, &y, &u, &v, &volume, &depth, &area, &initial_area, &bed, &number_density,
        &smoothing_length, &omega}) {
    compact(*field, flagged);
  }
  if (tracks_ages_) compact(entry_time, flagged);
  if (tracks_pathlines_) compact(pathline, flagged);
  if (label_count_ > 0) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < flagged.size(); ++i) {
      if (flagged[i]) continue;
      for (std::size_t l = 0; l < label_count_; ++l) {
        label_share[kept * label_count_ + l] = label_share[i * label_count_ + l];
      }
      ++kept;
    }
    label_share.resize(kept * label_count_);
  }
  fluid_count_ = x.size();
  mirror_end_ = fluid_count_;
  source.resize(fluid_count_);
  std::iota(source.begin(), source.end(), std::uint32_t{0});
}

double SweParticles::total_fluid_volume() const {
  // A fixed summation order makes the total bit-identical between runs, so conservation
  // checks can compare it exactly.
  double sum = 0.0;
  for (std::size_t i = 0; i < fluid_count_; ++i) sum += volume[i];
  return sum;
}

void SweParticles::track_provenance(std::size_t labels, bool ages) {
  if (size() != 0) {
    throw std::logic_error("SweParticles::track_provenance: only before the first particle");
  }
  label_count_ = labels;
  tracks_ages_ = ages;
}

void SweParticles::copy_provenance(std::size_t from, std::size_t to) {
  for (std::size_t l = 0; l < label_count_; ++l) {
    label_share[to * label_count_ + l] = label_share[from * label_count_ + l];
  }
  if (tracks_ages_) entry_time[to] = entry_time[from];
}

void SweParticles::mix_provenance(std::size_t a, double volume_a, std::size_t b, double volume_b) {
  const double total = volume_a + volume_b;
  for (std::size_t l = 0; l < label_count_; ++l) {
    double& share = label_share[a * label_count_ + l];
    share = (volume_a * share + volume_b * label_share[b * label_count_ + l]) / total;
  }
  if (tracks_ages_) entry_time[a] = (volume_a * entry_time[a] + volume_b * entry_time[b]) / total;
}

void SweParticles::mix_in(std::size_t i, double volume_m3, double added_m3, Origin origin) {
  const double total = volume_m3 + added_m3;
  for (std::size_t l = 0; l < label_count_; ++l) {
    double& share = label_share[i * label_count_ + l];
    share = (volume_m3 * share + (l == origin.label ? added_m3 : 0.0)) / total;
  }
  if (tracks_ages_) {
    entry_time[i] = (volume_m3 * entry_time[i] + added_m3 * origin.entry_time_s) / total;
  }
}

void SweParticles::track_pathlines() {
  if (size() != 0) {
    throw std::logic_error("SweParticles::track_pathlines: only before the first particle");
  }
  tracks_pathlines_ = true;
}

void SweParticles::hand_over_pathline(std::size_t absorbed, std::size_t kept) {
  if (!tracks_pathlines_ || pathline[absorbed] == kNoPathline) return;
  if (pathline[kept] != kNoPathline) {
    pathline_ends.push_back(
        {pathline[absorbed], x[absorbed], y[absorbed], PathlineEnd::Cause::merged, pathline[kept]});
  } else {
    pathline[kept] = pathline[absorbed];
  }
  pathline[absorbed] = kNoPathline;
}

double SweParticles::label_volume(std::size_t k) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < fluid_count_; ++i)
    sum += volume[i] * label_share[i * label_count_ + k];
  return sum;
}

}  // namespace swemps::particles
