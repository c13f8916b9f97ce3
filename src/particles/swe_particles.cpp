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
                             double a0, double zb) {
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
  for (std::vector<double>* field :
       {&x, &y, &u, &v, &volume, &depth, &area, &initial_area, &bed, &number_density,
        &smoothing_length, &omega}) {
    compact(*field, flagged);
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

}  // namespace swemps::particles
