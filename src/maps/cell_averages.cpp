#include "swemps/maps/cell_averages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

namespace swemps::maps {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The sub-point index range [first, last] within `reach` of `centre` along one axis.
struct IndexRange {
  long first, last;
};
IndexRange reach_range(double centre, double reach, double origin, double spacing) {
  const double lo = std::ceil((centre - reach - origin) / spacing);
  const double hi = std::floor((centre + reach - origin) / spacing);
  if (!(lo <= hi)) return {0, -1};  // none, or NaN
  return {static_cast<long>(lo), static_cast<long>(hi)};
}

}  // namespace

CellAverages::CellAverages(const swe::RegularGrid& grid, std::shared_ptr<const swe::BedSource> bed,
                           Bounds domain, double finest_spacing_m, std::size_t stored_sub_points)
    : grid_(grid), bed_(std::move(bed)), domain_(domain) {
  const double cell = std::min(grid.dx, grid.dy);
  resolved_length_m_ = std::max(cell, finest_spacing_m);
  // A spacing apart puts about 20 sub-points under a particle's support disc (radius 2.6
  // spacings at the conservative scheme's kappa of 1.3), and the shares move smoothly with the
  // particle because the kernel falls to zero at the support's edge.
  const double target = finest_spacing_m > 0.0 ? finest_spacing_m : cell;
  const double across = std::ceil(cell / target - 1e-9);
  sub_ = static_cast<std::size_t>(std::clamp(across, 1.0, static_cast<double>(kMaxSubdivisions)));
  sdx_ = grid.dx / static_cast<double>(sub_);
  sdy_ = grid.dy / static_cast<double>(sub_);
  sx0_ = grid.x0 - 0.5 * grid.dx + 0.5 * sdx_;
  sy0_ = grid.y0 - 0.5 * grid.dy + 0.5 * sdy_;
  snx_ = static_cast<long>(grid.nx * sub_);
  sny_ = static_cast<long>(grid.ny * sub_);
  // The bed at every sub-point, read once, unless that would take more memory than the
  // particles do in a large scene: then each share reads the bed where it falls.
  if (bed_ == nullptr || static_cast<double>(snx_) * static_cast<double>(sny_) >
                             static_cast<double>(stored_sub_points)) {
    return;
  }
  bed_at_sub_.assign(static_cast<std::size_t>(snx_ * sny_), 0.0);
#pragma omp parallel for schedule(static)
  for (long sk = 0; sk < sny_; ++sk) {
    const double y = sy0_ + static_cast<double>(sk) * sdy_;
    for (long si = 0; si < snx_; ++si) {
      bed_at_sub_[static_cast<std::size_t>(sk * snx_ + si)] =
          bed_->elevation(sx0_ + static_cast<double>(si) * sdx_, y);
    }
  }
}

double CellAverages::sub_bed(long si, long sk) const {
  if (bed_ == nullptr) return 0.0;
  if (!bed_at_sub_.empty() && si >= 0 && si < snx_ && sk >= 0 && sk < sny_) {
    return bed_at_sub_[static_cast<std::size_t>(sk * snx_ + si)];
  }
  // Not stored, or inside the domain but outside the map (grid bounds smaller than the
  // domain).
  return bed_->elevation(sx0_ + static_cast<double>(si) * sdx_,
                         sy0_ + static_cast<double>(sk) * sdy_);
}

double CellAverages::level(std::size_t cell, double depth_m) const {
  if (!(depth_m > 0.0) || cell >= grid_.nx * grid_.ny) return kNaN;
  const long sub = static_cast<long>(sub_);
  const long ci = static_cast<long>(cell % grid_.nx), ck = static_cast<long>(cell / grid_.nx);
  std::vector<double> ground;
  for (long sk = ck * sub; sk < (ck + 1) * sub; ++sk) {
    const double y = sy0_ + static_cast<double>(sk) * sdy_;
    if (y < domain_.y_min || y > domain_.y_max) continue;
    for (long si = ci * sub; si < (ci + 1) * sub; ++si) {
      const double x = sx0_ + static_cast<double>(si) * sdx_;
      if (x < domain_.x_min || x > domain_.x_max) continue;
      const double b = sub_bed(si, sk);
      if (!std::isnan(b)) ground.push_back(b);
    }
  }
  if (ground.empty()) return kNaN;
  std::sort(ground.begin(), ground.end());
  // With the k lowest sub-points wet, k eta - (their ground) = the volume over a sub-point's
  // area; the level is the first such eta that stays at or below the next sub-point's ground.
  const double volume_over_area = depth_m * grid_.dx * grid_.dy / (sdx_ * sdy_);
  double ground_sum = 0.0;
  for (std::size_t k = 1; k <= ground.size(); ++k) {
    ground_sum += ground[k - 1];
    const double eta = (volume_over_area + ground_sum) / static_cast<double>(k);
    if (k == ground.size() || eta <= ground[k]) return eta;
  }
  return kNaN;  // not reached
}

std::size_t CellAverages::cell_of_sub_point(long si, long sk, bool row_on_map) const {
  // A share inside the domain but off the map counts towards the total and is not mapped.
  if (!(row_on_map && si >= 0 && si < snx_)) return kOffMap;
  const long sub = static_cast<long>(sub_);
  return static_cast<std::size_t>(sk / sub) * grid_.nx + static_cast<std::size_t>(si / sub);
}

// Most particles are far from walls and edges: their kernel has no image, and a row's
// sub-points inside the support are a run that the kernel's values fill in one vectorised
// pass, with 1/h and the kernel's scale taken once. The sub-points of the box outside the disc
// (a fifth of them) are not visited. Why: the maps and flood statistics sampled all particles
// this way at every sample, a fifth of Thacker's run when each kernel was evaluated with its
// divisions and each sub-point tested against the images (docs/performance.md).
template <class Kernel>
double CellAverages::unmirrored_weights(const particles::SweParticles& p, std::size_t j,
                                        const SubRange& range, Scratch& scratch,
                                        std::vector<Share>& shares) const {
  const std::size_t first = shares.size();
  const double h = p.smoothing_length[j];
  const double support = swe::ParticleKernel::support(h);
  const double support2 = support * support;
  const double inverse_h = 1.0 / h;
  const double scale = Kernel::sigma() * inverse_h * inverse_h;  // sigma / h^2 in 2D
  const double surface = p.bed[j] + p.depth[j];
  const double xj = p.x[j], yj = p.y[j];
  const bool bed_stored = bed_ != nullptr && !bed_at_sub_.empty();
  double total = 0.0;
  for (long sk = range.k0; sk <= range.k1; ++sk) {
    const double y = sy0_ + static_cast<double>(sk) * sdy_;
    const double dy = yj - y;
    const double across = support2 - dy * dy;
    if (!(across > 0.0)) continue;
    // The row's run inside the disc, widened by a sub-point each side against round-off (the
    // kernel is zero there, and the test below is the exact one).
    const double half = std::sqrt(across);
    const double lo =
        std::max(static_cast<double>(range.i0), std::ceil((xj - half - sx0_) / sdx_) - 1.0);
    const double hi =
        std::min(static_cast<double>(range.i1), std::floor((xj + half - sx0_) / sdx_) + 1.0);
    if (!(lo <= hi)) continue;
    const long i0 = static_cast<long>(lo), i1 = static_cast<long>(hi);
    const auto count = static_cast<std::size_t>(i1 - i0 + 1);
    auto& w = scratch.row_weight;
    w.resize(count);
    double* weight = w.data();
    const double x0 = sx0_ + static_cast<double>(i0) * sdx_, spacing = sdx_;
    // An int index: the conversion of a 64-bit one to double does not vectorise.
    const int run = static_cast<int>(count);
#pragma omp simd
    for (int t = 0; t < run; ++t) {
      const double dx = xj - (x0 + static_cast<double>(t) * spacing);
      // The kernel's shape is zero from the support's edge on (q >= 2).
      weight[t] = scale * Kernel::shape(std::sqrt(dx * dx + dy * dy) * inverse_h);
    }
    // The row's cells, as cell_of_sub_point() finds them but without its divisions: one a
    // row, and one a sub-point only where a cell holds several sub-points.
    const bool row_on_map = sk >= 0 && sk < sny_;
    const long sub = static_cast<long>(sub_);
    const std::size_t row_cells = row_on_map ? static_cast<std::size_t>(sk / sub) * grid_.nx : 0;
    const double* bed_row = bed_stored && row_on_map
                                ? bed_at_sub_.data() + static_cast<std::size_t>(sk * snx_)
                                : nullptr;
    for (std::size_t t = 0; t < count; ++t) {
      if (!(weight[t] > 0.0)) continue;
      const long si = i0 + static_cast<long>(t);
      const bool on_map = row_on_map && si >= 0 && si < snx_;
      const double ground = bed_row && on_map ? bed_row[si] : sub_bed(si, sk);
      const double over_bed = surface - ground;
      if (!(over_bed > 0.0)) continue;  // ground above the particle's surface, or nodata
      const double share = weight[t] * over_bed;
      total += share;
      add_share(on_map ? row_cells + static_cast<std::size_t>(sub == 1 ? si : si / sub) : kOffMap,
                share, first, shares);
    }
  }
  return total;
}

template <class Kernel>
void CellAverages::shares_of(const particles::SweParticles& p, std::size_t j,
                             std::span<const std::uint32_t> ghosts, const Kernel& kernel,
                             Scratch& scratch, std::vector<Share>& shares) const {
  const std::size_t first = shares.size();
  const double h = p.smoothing_length[j];
  const double support = swe::ParticleKernel::support(h);
  // A particle that reaches no cell of the map puts nothing on it, whatever its shares.
  if (p.x[j] + support < grid_.x0 - 0.5 * grid_.dx ||
      p.x[j] - support > grid_.x0 + (static_cast<double>(grid_.nx) - 0.5) * grid_.dx ||
      p.y[j] + support < grid_.y0 - 0.5 * grid_.dy ||
      p.y[j] - support > grid_.y0 + (static_cast<double>(grid_.ny) - 0.5) * grid_.dy) {
    return;
  }
  const double surface = p.bed[j] + p.depth[j];
  // The kernel is centred on the particle and on its images: its ghosts behind the walls, as
  // in the depth sum, and its mirror images across the domain's edges where no wall ghost
  // stands already. Uniform water then reads uniform up to a wall or an edge. A sub-point
  // nearer one of the particle's ghosts than the particle lies behind that ghost's wall and
  // takes no share of it.
  auto& images = scratch.images;
  images.clear();
  images.push_back({p.x[j], p.y[j]});
  for (std::uint32_t g : ghosts) images.push_back({p.x[g], p.y[g]});
  const std::size_t wall_images = images.size();
  // Each of those mirrored across the domain's edges within the particle's reach.
  const double same = 1e-9 * support;
  const auto known = [&](const Point& q) {
    return std::any_of(images.begin(), images.end(), [&](const Point& r) {
      return std::abs(q[0] - r[0]) < same && std::abs(q[1] - r[1]) < same;
    });
  };
  for (std::size_t m = 0; m < wall_images; ++m) {
    const Point source = images[m];
    std::array<double, 3> edge_x{source[0]}, edge_y{source[1]};
    std::size_t nex = 1, ney = 1;
    if (p.x[j] - domain_.x_min < support) edge_x[nex++] = 2.0 * domain_.x_min - source[0];
    if (domain_.x_max - p.x[j] < support) edge_x[nex++] = 2.0 * domain_.x_max - source[0];
    if (p.y[j] - domain_.y_min < support) edge_y[ney++] = 2.0 * domain_.y_min - source[1];
    if (domain_.y_max - p.y[j] < support) edge_y[ney++] = 2.0 * domain_.y_max - source[1];
    for (std::size_t a = 0; a < nex; ++a) {
      for (std::size_t b = 0; b < ney; ++b) {
        if (a == 0 && b == 0) continue;  // the image itself
        const Point image{edge_x[a], edge_y[b]};
        if (!known(image)) images.push_back(image);
      }
    }
  }
  auto [i0, i1] = reach_range(p.x[j], support, sx0_, sdx_);
  auto [k0, k1] = reach_range(p.y[j], support, sy0_, sdy_);
  const auto first_inside = [](double edge, double origin, double spacing) {
    return static_cast<long>(std::ceil((edge - origin) / spacing));
  };
  const auto last_inside = [](double edge, double origin, double spacing) {
    return static_cast<long>(std::floor((edge - origin) / spacing));
  };
  i0 = std::max(i0, first_inside(domain_.x_min, sx0_, sdx_));
  i1 = std::min(i1, last_inside(domain_.x_max, sx0_, sdx_));
  k0 = std::max(k0, first_inside(domain_.y_min, sy0_, sdy_));
  k1 = std::min(k1, last_inside(domain_.y_max, sy0_, sdy_));
  const double support2 = support * support;
  double total = 0.0;
  if (images.size() == 1) {
    total = unmirrored_weights<Kernel>(p, j, {i0, i1, k0, k1}, scratch, shares);
  } else {
    for (long sk = k0; sk <= k1; ++sk) {
      const double y = sy0_ + static_cast<double>(sk) * sdy_;
      const bool row_on_map = sk >= 0 && sk < sny_;
      for (long si = i0; si <= i1; ++si) {
        const double x = sx0_ + static_cast<double>(si) * sdx_;
        const double own_dx = p.x[j] - x, own_dy = p.y[j] - y;
        const double own_r2 = own_dx * own_dx + own_dy * own_dy;
        bool behind_wall = false;
        double kernel_sum = own_r2 < support2 ? kernel.w(std::sqrt(own_r2), h) : 0.0;
        for (std::size_t m = 1; m < images.size(); ++m) {
          const double dx = images[m][0] - x, dy = images[m][1] - y;
          const double r2 = dx * dx + dy * dy;
          if (m < wall_images && r2 < own_r2) {
            behind_wall = true;
            break;
          }
          if (r2 < support2) kernel_sum += kernel.w(std::sqrt(r2), h);
        }
        if (behind_wall || !(kernel_sum > 0.0)) continue;
        const double over_bed = surface - sub_bed(si, sk);
        if (!(over_bed > 0.0)) continue;  // ground above the particle's surface, or nodata
        const double weight = kernel_sum * over_bed;
        total += weight;
        add_share(cell_of_sub_point(si, sk, row_on_map), weight, first, shares);
      }
    }
  }
  if (total > 0.0) {
    const double inverse = 1.0 / total;
    for (std::size_t s = first; s < shares.size(); ++s) shares[s].fraction *= inverse;
    return;
  }
  // No sub-point under the particle's reach is wet by its surface (a particle smaller than
  // the sub-point spacing, say): the whole volume goes to the cell holding it.
  shares.resize(first);
  const double col = std::floor((p.x[j] - (grid_.x0 - 0.5 * grid_.dx)) / grid_.dx);
  const double row = std::floor((p.y[j] - (grid_.y0 - 0.5 * grid_.dy)) / grid_.dy);
  const bool on_map = col >= 0.0 && col < static_cast<double>(grid_.nx) && row >= 0.0 &&
                      row < static_cast<double>(grid_.ny);
  shares.push_back(
      {on_map ? static_cast<std::size_t>(row) * grid_.nx + static_cast<std::size_t>(col) : kOffMap,
       1.0});
}

CellFields CellAverages::fields(const particles::SweParticles& p,
                                const swe::ParticleKernel& w) const {
  const std::size_t cells = grid_.nx * grid_.ny;
  CellFields out{std::vector<double>(cells, 0.0), std::vector<double>(cells, kNaN),
                 std::vector<double>(cells, kNaN), std::vector<double>(cells, kNaN)};
  const std::size_t labels = p.label_count();
  if (labels > 0) out.label_depth.assign(labels * cells, 0.0);
  if (p.tracks_ages()) out.entry_time.assign(cells, kNaN);
  const std::size_t n = p.fluid_count();
  if (n == 0 || cells == 0) return out;
  std::vector<double> qx(cells, 0.0), qy(cells, 0.0), volume_surface(cells, 0.0);
  // Volumes times entry times until they are divided by the volumes below.
  if (p.tracks_ages()) out.entry_time.assign(cells, 0.0);
  // Blocks of particles find their shares in parallel, each into its own list with the
  // particles' ranges in it; the lists are then added in particle order, so that the maps do
  // not depend on the number of threads.
  constexpr std::size_t kBlock = 256;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  if (shares_.size() < blocks) shares_.resize(blocks);
  if (ends_.size() < n) ends_.resize(n);
  // Each fluid particle's mirror images behind walls, grouped by the particle they mirror
  // (counting sort). The water an open boundary's ghosts stand for is beyond the domain: no
  // cell of the map takes a share of it.
  const std::size_t mirrors = p.mirror_end();
  ghost_start_.assign(n + 1, 0);
  for (std::size_t g = n; g < mirrors; ++g) ++ghost_start_[p.source[g] + 1];
  for (std::size_t j = 0; j < n; ++j) ghost_start_[j + 1] += ghost_start_[j];
  ghost_list_.resize(mirrors - n);
  {
    std::vector<std::size_t> next(ghost_start_.begin(), ghost_start_.end() - 1);
    for (std::size_t g = n; g < mirrors; ++g) {
      ghost_list_[next[p.source[g]]++] = static_cast<std::uint32_t>(g);
    }
  }
  swe::with_kernel_shape(w.shape(), [&](const auto& kernel) {
#pragma omp parallel for schedule(dynamic, 1)
    for (long b = 0; b < static_cast<long>(blocks); ++b) {
      auto& list = shares_[static_cast<std::size_t>(b)];
      list.clear();
      Scratch scratch;
      const std::size_t j1 = std::min(n, (static_cast<std::size_t>(b) + 1) * kBlock);
      for (std::size_t j = static_cast<std::size_t>(b) * kBlock; j < j1; ++j) {
        const std::span<const std::uint32_t> ghosts(ghost_list_.data() + ghost_start_[j],
                                                    ghost_start_[j + 1] - ghost_start_[j]);
        shares_of(p, j, ghosts, kernel, scratch, list);
        ends_[j] = list.size();
      }
    }
  });
  for (std::size_t b = 0; b < blocks; ++b) {
    const auto& list = shares_[b];
    std::size_t s = 0;
    const std::size_t j1 = std::min(n, (b + 1) * kBlock);
    for (std::size_t j = b * kBlock; j < j1; ++j) {
      const std::size_t s_first = s;
      const double volume = p.volume[j];
      const double momentum_x = volume * p.u[j], momentum_y = volume * p.v[j];
      const double volume_times_surface = volume * (p.bed[j] + p.depth[j]);
      for (; s < ends_[j]; ++s) {
        const Share& share = list[s];
        if (share.cell == kOffMap) continue;
        out.depth[share.cell] += share.fraction * volume;
        qx[share.cell] += share.fraction * momentum_x;
        qy[share.cell] += share.fraction * momentum_y;
        volume_surface[share.cell] += share.fraction * volume_times_surface;
      }
      if (labels > 0 || p.tracks_ages()) add_provenance(p, j, list, s_first, ends_[j], out);
    }
  }
  const double cell_area = grid_.dx * grid_.dy;
  for (std::size_t c = 0; c < cells; ++c) {
    const double volume = out.depth[c];
    if (!(volume > 0.0)) continue;
    out.depth[c] = volume / cell_area;
    out.u[c] = qx[c] / volume;
    out.v[c] = qy[c] / volume;
    out.surface[c] = volume_surface[c] / volume;
  }
  for (double& volume : out.label_depth) volume /= cell_area;
  for (std::size_t c = 0; c < out.entry_time.size(); ++c) {
    // The volume is the cell's before it was divided by the area: its depth times the area.
    const double volume = out.depth[c] * cell_area;
    out.entry_time[c] = volume > 0.0 ? out.entry_time[c] / volume : kNaN;
  }
  return out;
}

void CellAverages::add_provenance(const particles::SweParticles& p, std::size_t j,
                                  const std::vector<Share>& list, std::size_t first,
                                  std::size_t end, CellFields& out) {
  const std::size_t labels = p.label_count();
  const std::size_t cells = grid_cells(out);
  const double volume = p.volume[j];
  for (std::size_t s = first; s < end; ++s) {
    const Share& share = list[s];
    if (share.cell == kOffMap) continue;
    const double part = share.fraction * volume;
    for (std::size_t k = 0; k < labels; ++k) {
      out.label_depth[k * cells + share.cell] += part * p.label_share[j * labels + k];
    }
    if (!out.entry_time.empty()) out.entry_time[share.cell] += part * p.entry_time[j];
  }
}

}  // namespace swemps::maps
