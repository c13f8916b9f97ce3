#include "swemps/splitting/particle_splitting.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/swe/operators.hpp"

namespace swemps::splitting {

MomentMatrix moment_matrix(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                           const swe::ParticleKernel& w, std::size_t i) {
  MomentMatrix c;
  for (std::uint32_t j : nl.row(i)) {
    const double dx = p.x[j] - p.x[i];
    const double dy = p.y[j] - p.y[i];
    const double wij = w.pair_w(p, i, j, std::sqrt(dx * dx + dy * dy));
    c.xx += wij * dx * dx;
    c.xy += wij * dx * dy;
    c.yy += wij * dy * dy;
  }
  return c;
}

namespace {

std::array<double, 2> major_axis(const MomentMatrix& c) {
  // Larger eigenvalue of [[xx, xy], [xy, yy]]; of the two equivalent forms of its eigenvector,
  // (lambda - yy, xy) and (xy, lambda - xx), take the longer one: it is the better
  // conditioned, and it is exact for a diagonal matrix.
  const double half_trace = 0.5 * (c.xx + c.yy);
  const double half_gap = 0.5 * (c.xx - c.yy);
  const double lambda = half_trace + std::sqrt(half_gap * half_gap + c.xy * c.xy);
  std::array<double, 2> a{lambda - c.yy, c.xy}, b{c.xy, lambda - c.xx};
  const double la = std::hypot(a[0], a[1]), lb = std::hypot(b[0], b[1]);
  const auto& v = la >= lb ? a : b;
  const double length = std::max(la, lb);
  // Isotropic to round-off: no preferred direction.
  if (!(length > 1e-12 * std::max(std::abs(lambda), 1e-300))) return {1.0, 0.0};
  return {v[0] / length, v[1] / length};
}

}  // namespace

std::array<double, 2> split_direction(const MomentMatrix& c, SplitAxis axis) {
  const auto t = major_axis(c);
  if (axis == SplitAxis::major) return t;
  // C is symmetric: its other eigenvector is perpendicular to the first.
  return {-t[1], t[0]};
}

ParticleSplitting::ParticleSplitting(SplittingSettings settings,
                                     std::vector<boundaries::WallSegment> walls)
    : settings_(settings), walls_(std::move(walls)) {}

bool ParticleSplitting::crosses_wall(double x0, double y0, double x1, double y1) const {
  return walls_.crosses_any({x0, y0}, {x1, y1});
}

bool ParticleSplitting::plan_split(const swe::StepContext& context, std::size_t i,
                                   Plan& plan) const {
  const auto& p = context.particles;
  const double half_separation = 0.5 * settings_.alpha_s * std::sqrt(p.area[i]);  // eq 10
  const auto t =
      split_direction(moment_matrix(p, context.neighbors, context.kernel, i), settings_.axis);
  // A daughter must stay on the parent's side of every wall: along t if possible, else
  // across it (near a wall the neighbours often spread along it anyway).
  std::array<double, 2> offset{};
  bool placed = false;
  for (const auto& dir : {t, std::array<double, 2>{-t[1], t[0]}}) {
    offset = {half_separation * dir[0], half_separation * dir[1]};
    if (!crosses_wall(p.x[i], p.y[i], p.x[i] + offset[0], p.y[i] + offset[1]) &&
        !crosses_wall(p.x[i], p.y[i], p.x[i] - offset[0], p.y[i] - offset[1])) {
      placed = true;
      break;
    }
  }
  if (!placed) return false;

  // eq 12: first-order Taylor expansion of u and h to the daughters' positions, with the
  // MPS gradient (eq 6).
  const auto& nl = context.neighbors;
  const double n_i = swe::number_density_at(p, nl, context.kernel, i);
  const auto grad_u = swe::mps_gradient_at(p, nl, context.kernel, i, p.u, n_i);
  const auto grad_v = swe::mps_gradient_at(p, nl, context.kernel, i, p.v, n_i);
  const auto grad_h = swe::mps_gradient_at(p, nl, context.kernel, i, p.depth, n_i);
  const double du = offset[0] * grad_u[0] + offset[1] * grad_u[1];
  const double dv = offset[0] * grad_v[0] + offset[1] * grad_v[1];
  const double h = p.depth[i];
  // Limited to half the depth so that a steep local gradient can never leave a daughter dry:
  // each daughter keeps at least a quarter of the parent's volume.
  const double dh = std::clamp(offset[0] * grad_h[0] + offset[1] * grad_h[1], -0.5 * h, 0.5 * h);

  // Volumes: the eq 12 depth times half the parent's area. The larger share is computed and
  // the smaller one taken as the remainder, a subtraction that is exact in floating point
  // (the larger lies within [V/2, V]), so the two add up to V exactly.
  const double volume = p.volume[i];
  const double larger = volume * (h + std::abs(dh)) / (2.0 * h);
  const double smaller = volume - larger;
  const double volume_a = dh >= 0.0 ? larger : smaller;
  const double volume_b = dh >= 0.0 ? smaller : larger;
  // eq 12 velocities plus a common shift c chosen so that V_a u_a + V_b u_b = V u exactly:
  // (V_a - V_b) du + V c = 0.
  const double shift = -(volume_a - volume_b) / volume;
  plan.parent = i;
  plan.area = 0.5 * p.area[i];
  plan.a = {p.x[i] + offset[0],       p.y[i] + offset[1], p.u[i] + du + shift * du,
            p.v[i] + dv + shift * dv, volume_a,           h + dh};
  plan.b = {p.x[i] - offset[0],       p.y[i] - offset[1], p.u[i] - du + shift * du,
            p.v[i] - dv + shift * dv, volume_b,           h - dh};
  return true;
}

void ParticleSplitting::apply(swe::StepContext& context) {
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();
  plans_.clear();
  // Which particles have grown past the threshold, in parallel (few have); the plans are then
  // made in index order, so the particles the cap refuses never depend on the threads.
  oversized_.assign(n, 0);
  parallel_for(n, [&](std::size_t i) {
    const double area = p.area[i], reference = p.initial_area[i];
    const double cap = settings_.radius_cap_area_ratio;
    const bool alone = cap > 0.0 && area >= cap * reference;
    const bool film = p.volume[i] < settings_.min_depth_m * reference;
    oversized_[i] = area > settings_.area_ratio_threshold * reference && !alone && !film;
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (!oversized_[i]) continue;
    if (settings_.max_particles != 0 && n + plans_.size() >= settings_.max_particles) {
      ++refused_at_cap_;
      continue;
    }
    Plan plan{};
    if (plan_split(context, i, plan)) {
      plans_.push_back(plan);
    } else {
      ++refused_at_walls_;
    }
  }
  if (plans_.empty()) return;

  // The plans used the ghosts; the particle set changes only now, and the simulation
  // rebuilds ghosts, neighbours and depths for the new set.
  p.drop_ghosts();
  for (const Plan& plan : plans_) {
    const std::size_t i = plan.parent;
    if (context.changed) context.changed->push_back(static_cast<std::uint32_t>(i));
    const Daughter& a = plan.a;
    p.x[i] = a.x;
    p.y[i] = a.y;
    p.u[i] = a.u;
    p.v[i] = a.v;
    p.volume[i] = a.volume;
    p.depth[i] = a.depth;
    p.area[i] = plan.area;
    // Each daughter is first searched with its parent's radius; the depth iteration then finds
    // its own. The radius of half the parent's area would be too short a start where a
    // daughter lands at a free edge (measured: 17 % short, a dam break's face), and a radius
    // that outgrows its search costs every particle a second search and sum.
    const double parent_radius = p.smoothing_length[i];
    const Daughter& b = plan.b;
    p.add_fluid(b.x, b.y, b.u, b.v, b.volume, b.depth, p.initial_area[i], p.bed[i]);
    p.copy_provenance(i, p.fluid_count() - 1);
    p.area.back() = plan.area;
    p.smoothing_length.back() = parent_radius;
  }
  splits_ += plans_.size();
}

std::string ParticleSplitting::report() const {
  std::string text = std::to_string(splits_) + " splits";
  if (refused_at_walls_ > 0) {
    text += ", " + std::to_string(refused_at_walls_) +
            " split attempts refused (a daughter would cross a wall)";
  }
  if (refused_at_cap_ > 0) {
    text += ", " + std::to_string(refused_at_cap_) + " split attempts refused at the cap of " +
            std::to_string(settings_.max_particles) + " particles";
  }
  return text;
}

void ParticleSplitting::save_state(swe::StateWriter& out) const {
  for (const std::size_t n : {splits_, refused_at_walls_, refused_at_cap_}) out.count(n);
}

void ParticleSplitting::restore_state(swe::StateReader& in) {
  splits_ = in.count();
  refused_at_walls_ = in.count();
  refused_at_cap_ = in.count();
}

}  // namespace swemps::splitting
