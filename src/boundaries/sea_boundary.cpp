#include "swemps/boundaries/sea_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "swemps/boundaries/particle_removal.hpp"
#include "swemps/neighbors/parallel.hpp"

namespace swemps::boundaries {

namespace {

// A buffer shallower than this fraction of a spacing holds no water: the sea beyond the line
// has run dry there, and no ghost stands for it.
constexpr double kDriestBuffer = 1e-6;

// The particles whose state makes a stretch's: those within this many spacings of the line,
// the two rows beside it, the nearer weighing more.
constexpr double kStateBand = 2.0;

[[noreturn]] void reject(std::size_t index, const std::array<double, 2>& point,
                         const std::string& problem) {
  std::ostringstream msg;
  msg << "level series point " << index + 1 << " (t = " << point[0] << " s, level " << point[1]
      << " m): " << problem;
  throw std::invalid_argument(msg.str());
}

// A square lattice's summed area over its cell, A / l^2 (1 / (l^2 sum_j W)), for uniform water
// under the conservative scheme's radius rule h = kappa sqrt(A) (docs/method.md, "The
// conservative scheme"): a scale-free fixed point, found once. Water seeded with depth d x
// cell sums to d / ratio. The boundary speaks in summed depths and gives its own lattice
// particles h_b x ratio x cell, so that a sea at rest meets a buffer it cannot tell from more
// of itself.
double lattice_area_ratio(const swe::Settings& settings) {
  const swe::ParticleKernel kernel(settings.kernel);
  double ratio = 1.0;
  for (int pass = 0; pass < 50; ++pass) {
    const double h = settings.kappa * std::sqrt(ratio);
    const int reach = static_cast<int>(std::ceil(swe::ParticleKernel::support(h))) + 1;
    double sum = 0.0;
    for (int i = -reach; i <= reach; ++i) {
      for (int j = -reach; j <= reach; ++j) sum += kernel.w(std::hypot(i, j), h);
    }
    const double next = 1.0 / sum;
    const bool settled = std::abs(next - ratio) <= 1e-14 * ratio;
    ratio = next;
    if (settled) break;
  }
  return ratio;
}

}  // namespace

LevelSeries::LevelSeries(std::vector<std::array<double, 2>> points) : points_(std::move(points)) {
  if (points_.empty()) throw std::invalid_argument("level series: no points");
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const auto& p = points_[k];
    if (!std::isfinite(p[0])) reject(k, p, "time is not a finite number");
    if (!std::isfinite(p[1])) reject(k, p, "level is not a finite number");
    if (k > 0 && !(p[0] > points_[k - 1][0])) {
      std::ostringstream problem;
      problem << "time is not after the previous point's " << points_[k - 1][0] << " s";
      reject(k, p, problem.str());
    }
  }
}

double LevelSeries::level(double t) const {
  if (t <= points_.front()[0]) return points_.front()[1];
  if (t >= points_.back()[0]) return points_.back()[1];
  const auto after = std::upper_bound(points_.begin(), points_.end(), t,
                                      [](double time, const auto& p) { return time < p[0]; });
  const auto& b = *after;
  const auto& a = *(after - 1);
  return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
}

SeaBoundary::SeaBoundary(SeaBoundarySettings settings) : settings_(std::move(settings)) {
  if (settings_.name.empty()) throw std::invalid_argument("sea boundary: empty name");
  const std::string who = "sea boundary '" + settings_.name + "': ";
  const std::array<double, 2> d{settings_.to[0] - settings_.from[0],
                                settings_.to[1] - settings_.from[1]};
  length_m_ = std::hypot(d[0], d[1]);
  if (!(length_m_ > 0.0) || !std::isfinite(length_m_))
    throw std::invalid_argument(who + "the line has zero or non-finite length");
  along_ = {d[0] / length_m_, d[1] / length_m_};
  const double norm = std::hypot(settings_.outward[0], settings_.outward[1]);
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw std::invalid_argument(who + "the outward direction is zero or not finite");
  outward_ = {settings_.outward[0] / norm, settings_.outward[1] / norm};
  if (std::abs(outward_[0] * along_[0] + outward_[1] * along_[1]) > 1e-9)
    throw std::invalid_argument(who + "the outward direction is not normal to the line");
  const double l = settings_.spacing_m;
  if (!(l > 0.0) || !std::isfinite(l))
    throw std::invalid_argument(who + "the spacing must be a positive number of metres");
  if (!std::isfinite(settings_.still_level_m))
    throw std::invalid_argument(who + "the still level is not a finite number");
  stretches_.resize(static_cast<std::size_t>(std::max(1.0, std::round(length_m_ / l))));
  width_m_ = length_m_ / static_cast<double>(stretches_.size());
}

double SeaBoundary::boundary_level(double t) const {
  if (settings_.level && t <= settings_.level->end_time()) return settings_.level->level(t);
  return settings_.level ? settings_.level->last_level() : settings_.still_level_m;
}

std::array<double, 2> SeaBoundary::place(double x, double y) const {
  const double rx = x - settings_.from[0], ry = y - settings_.from[1];
  return {-(rx * outward_[0] + ry * outward_[1]), rx * along_[0] + ry * along_[1]};
}

std::size_t SeaBoundary::stretch_at(double along) const {
  const double f = along / width_m_;
  return static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(stretches_.size()) - 1.0));
}

double SeaBoundary::summed_depth(double level, double bed) const {
  return std::max(0.0, level - bed) / lattice_ratio_;
}

double SeaBoundary::still_depth(double x, double y, double t) const {
  return summed_depth(boundary_level(t), settings_.bed ? settings_.bed->elevation(x, y) : 0.0);
}

std::array<double, 2> SeaBoundary::velocity(const State& s) const {
  return {s.normal_speed * outward_[0] + s.tangential_speed * along_[0],
          s.normal_speed * outward_[1] + s.tangential_speed * along_[1]};
}

SeaBoundary::State SeaBoundary::boundary_state(const particles::SweParticles& p,
                                               std::size_t i) const {
  const double g = gravity_m_s2_;
  const double h = p.depth[i];
  const double un = p.u[i] * outward_[0] + p.v[i] * outward_[1];
  const double ut = p.u[i] * along_[0] + p.v[i] * along_[1];
  const double c = std::sqrt(g * h);
  if (un >= c) return {h, un, ut};  // both characteristics leave
  const double still = summed_depth(boundary_level(time_s_), p.bed[i]);
  const double outgoing = un + 2.0 * c;
  if (settings_.level && time_s_ <= settings_.level->end_time()) {
    const double cb = std::sqrt(g * still);
    return {still, outgoing - 2.0 * cb, ut};
  }
  const double incoming = -2.0 * std::sqrt(g * still);
  const double cb = std::max(0.0, 0.25 * (outgoing - incoming));
  return {cb * cb / g, 0.5 * (outgoing + incoming), ut};
}

void SeaBoundary::fill_buffer() {
  // Rows a spacing apart from half a spacing beyond the line, one particle a stretch, holding
  // the sea at rest (or the series' first level).
  const double l = settings_.spacing_m;
  for (std::size_t k = 0; k < stretches_.size(); ++k) {
    const double centre = (static_cast<double>(k) + 0.5) * width_m_;
    const double x = settings_.from[0] + centre * along_[0];
    const double y = settings_.from[1] + centre * along_[1];
    stretches_[k].held = {still_depth(x, y, time_s_), 0.0, 0.0};
    for (double outside = 0.5 * l; outside < layer_m_; outside += l) {
      buffer_.push_back({x + outside * outward_[0], y + outside * outward_[1], l * width_m_, true});
    }
  }
  filled_ = true;
}

void SeaBoundary::add_ghosts(particles::SweParticles& p, double reach,
                             const swe::Settings& settings, double time_s) {
  gravity_m_s2_ = settings.gravity_m_s2;
  time_s_ = time_s;
  const double l = settings_.spacing_m;
  layer_m_ = std::max(1.0, std::ceil(reach / l - 1e-9)) * l;
  if (lattice_ratio_ == 0.0) lattice_ratio_ = lattice_area_ratio(settings);
  if (!filled_) fill_buffer();
  first_ghost_ = p.size();
  ghosts_.clear();
  // Each stretch's ghosts take the radius of the fluid particle nearest the line beside it (or
  // beside any stretch): particles of the size the water there has.
  constexpr auto kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> source(stretches_.size(), kNone);
  std::vector<double> nearest(stretches_.size(), std::numeric_limits<double>::infinity());
  std::uint32_t any = kNone;
  double any_nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const auto [inside, along] = place(p.x[i], p.y[i]);
    if (!(inside > 0.0) || !(inside <= layer_m_) || !(along >= 0.0) || !(along < length_m_))
      continue;
    const std::size_t k = stretch_at(along);
    if (inside < nearest[k]) {
      nearest[k] = inside;
      source[k] = static_cast<std::uint32_t>(i);
    }
    if (inside < any_nearest) {
      any_nearest = inside;
      any = static_cast<std::uint32_t>(i);
    }
  }
  if (any == kNone) return;  // no water beside the line: nothing for a buffer to act on
  for (std::size_t j = 0; j < buffer_.size(); ++j) {
    const BufferParticle& b = buffer_[j];
    const auto [inside, along] = place(b.x, b.y);
    const std::size_t k = stretch_at(along);
    const State& s = stretches_[k].held;
    if (!(s.depth > kDriestBuffer * l)) continue;
    const std::uint32_t from = source[k] != kNone ? source[k] : any;
    const auto [u, v] = velocity(s);
    const BufferGhost ghost{static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(k)};
    add_ghost_of(p, from, ghost, b.x, b.y, u, v);
    // Where a wall meets the line, the buffer's mirror image across it (the wall normal to
    // the line there), its velocity along the line reversed.
    const double un = s.normal_speed, ut = s.tangential_speed;
    const double mirrored_u = un * outward_[0] - ut * along_[0];
    const double mirrored_v = un * outward_[1] - ut * along_[1];
    if (settings_.walled_ends[0] && along < reach) {
      add_ghost_of(p, from, ghost, b.x - 2.0 * along * along_[0], b.y - 2.0 * along * along_[1],
                   mirrored_u, mirrored_v);
    }
    const double to_end = length_m_ - along;
    if (settings_.walled_ends[1] && to_end < reach) {
      add_ghost_of(p, from, ghost, b.x + 2.0 * to_end * along_[0], b.y + 2.0 * to_end * along_[1],
                   mirrored_u, mirrored_v);
    }
  }
}

void SeaBoundary::add_ghost_of(particles::SweParticles& p, std::uint32_t source, BufferGhost ghost,
                               double x, double y, double u, double v) {
  p.add_ghost(source, x, y, u, v);
  // Its water, for the depth sums of the fluid beside it.
  p.volume[p.size() - 1] =
      stretches_[ghost.stretch].held.depth * summed_area(buffer_[ghost.buffer]);
  ghosts_.push_back(ghost);
}

void SeaBoundary::set_ghost_fields(particles::SweParticles& p) {
  // The ghosts' own depth and area: the buffer's (their radius and the rest are their source
  // particle's, copied).
  for (std::size_t g = 0; g < ghosts_.size(); ++g) {
    const std::size_t k = first_ghost_ + g;
    p.depth[k] = stretches_[ghosts_[g].stretch].held.depth;
    p.area[k] = summed_area(buffer_[ghosts_[g].buffer]);
  }
  // What the stretches measure for the next step: the boundary states of the fluid particles
  // in the rows beside the line, weighted by a tent across the line (1 at the line, 0 at the
  // band's edge) and one along it (shared between the two nearest stretch centres), so that a
  // particle entering the band or passing from one stretch to the next changes the state
  // smoothly, not by a particle's share at once.
  const double band = kStateBand * settings_.spacing_m;
  const auto last = static_cast<double>(stretches_.size() - 1);
  std::vector<double> weight(stretches_.size(), 0.0);
  for (auto& s : stretches_) s.measured = {};
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const auto [inside, along] = place(p.x[i], p.y[i]);
    if (!(inside > 0.0) || !(inside < band) || !(along >= 0.0) || !(along < length_m_)) continue;
    const State b = boundary_state(p, i);
    const double across = 1.0 - inside / band;
    const double f = std::clamp(along / width_m_ - 0.5, 0.0, last);
    const auto k0 = static_cast<std::size_t>(std::floor(f));
    const std::size_t k1 = std::min(k0 + 1, stretches_.size() - 1);
    const double share = f - static_cast<double>(k0);
    for (const auto& [k, w] :
         {std::pair{k0, across * (1.0 - share)}, std::pair{k1, across * share}}) {
      if (!(w > 0.0)) continue;
      State& m = stretches_[k].measured;
      m.depth += w * b.depth;
      m.normal_speed += w * b.normal_speed;
      m.tangential_speed += w * b.tangential_speed;
      weight[k] += w;
    }
  }
  for (std::size_t k = 0; k < stretches_.size(); ++k) {
    Stretch& s = stretches_[k];
    s.beside = weight[k] > 0.0;
    if (!s.beside) continue;
    s.measured.depth /= weight[k];
    s.measured.normal_speed /= weight[k];
    s.measured.tangential_speed /= weight[k];
  }
}

void SeaBoundary::apply(swe::StepContext& context) {
  const double dt = context.dt_s;
  const double l = settings_.spacing_m;
  auto& p = context.particles;
  // The states this step's buffer moves with and the next step's ghosts hold: those measured
  // as the step began. A stretch with no water beside it holds the still sea, at rest.
  for (std::size_t k = 0; k < stretches_.size(); ++k) {
    Stretch& s = stretches_[k];
    if (s.beside) {
      s.held = s.measured;
    } else {
      const double centre = (static_cast<double>(k) + 0.5) * width_m_;
      s.held = {still_depth(settings_.from[0] + centre * along_[0],
                            settings_.from[1] + centre * along_[1], context.time_s + dt),
                0.0, 0.0};
    }
  }
  for (BufferParticle& b : buffer_) {
    const auto [inside, along] = place(b.x, b.y);
    const auto [u, v] = velocity(stretches_[stretch_at(along)].held);
    b.x += dt * u;
    b.y += dt * v;
  }
  // Fluid beyond the line joins the buffer where it is. A non-finite position is left alone,
  // for the finiteness check of the next step to name.
  const std::size_t n = p.fluid_count();
  beyond_.assign(n, 0);
  parallel_for(n, [&](std::size_t i) {
    const auto [inside, along] = place(p.x[i], p.y[i]);
    beyond_[i] = inside <= 0.0 && along >= 0.0 && along < length_m_;
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (beyond_[i]) buffer_.push_back({p.x[i], p.y[i], p.area[i], false});
  }
  const Removal removal = remove_flagged(p, beyond_, context.ledger);
  particles_removed_ += removal.particles;
  removed_m3_ += removal.volume_m3;
  // Buffer carried into the domain becomes water; buffer past the layer, or beside it, goes.
  std::vector<BufferParticle> kept;
  kept.reserve(buffer_.size());
  std::vector<double> outermost(stretches_.size(), -0.5 * l);
  for (const BufferParticle& b : buffer_) {
    const auto [inside, along] = place(b.x, b.y);
    if (!(along >= 0.0) || !(along < length_m_) || -inside > layer_m_) continue;
    const std::size_t k = stretch_at(along);
    const State& s = stretches_[k].held;
    if (inside > 0.0) {
      if (!(s.depth > kDriestBuffer * l)) continue;
      const double volume = s.depth * summed_area(b);
      const auto [u, v] = velocity(s);
      const double bed = settings_.bed ? settings_.bed->elevation(b.x, b.y) : 0.0;
      p.add_fluid(b.x, b.y, u, v, volume, s.depth, b.made ? b.area_m2 : summed_area(b), bed,
                  {settings_.label, context.time_s + dt});
      context.ledger.added_m3 += volume;
      context.ledger.add_to_label(settings_.label, volume);
      added_m3_ += volume;
      ++particles_added_;
      continue;
    }
    outermost[k] = std::max(outermost[k], -inside);
    kept.push_back(b);
  }
  buffer_.swap(kept);
  // Topped up at the outer edge, a row at a time, where the buffer has moved in by a row.
  for (std::size_t k = 0; k < stretches_.size(); ++k) {
    const double centre = (static_cast<double>(k) + 0.5) * width_m_;
    for (double outside = outermost[k] + l; outside <= layer_m_ - 0.5 * l + 1e-9 * l;
         outside += l) {
      buffer_.push_back({settings_.from[0] + centre * along_[0] + outside * outward_[0],
                         settings_.from[1] + centre * along_[1] + outside * outward_[1],
                         l * width_m_, true});
    }
  }
}

double SeaBoundary::summed_area(const BufferParticle& b) const {
  return b.made ? lattice_ratio_ * b.area_m2 : b.area_m2;
}

std::string SeaBoundary::report() const {
  std::ostringstream out;
  out << particles_added_ << " particles, " << added_m3_ << " m3 in; " << particles_removed_
      << " particles, " << removed_m3_ << " m3 out";
  return out.str();
}

void SeaBoundary::save_state(swe::StateWriter& out) const {
  // The buffer and the states it holds decide the next step's ghosts; what the stretches
  // measure is measured again as the restored state is refreshed.
  std::vector<double> held, buffer;
  for (const auto& s : stretches_) {
    held.insert(held.end(), {s.held.depth, s.held.normal_speed, s.held.tangential_speed});
  }
  for (const auto& b : buffer_)
    buffer.insert(buffer.end(), {b.x, b.y, b.area_m2, b.made ? 1.0 : 0.0});
  out.numbers(held);
  out.numbers(buffer);
  out.count(filled_ ? 1 : 0);
  out.number(added_m3_);
  out.number(removed_m3_);
  out.count(particles_added_);
  out.count(particles_removed_);
}

void SeaBoundary::restore_state(swe::StateReader& in) {
  const std::vector<double> held = in.numbers();
  const std::vector<double> buffer = in.numbers();
  if (held.size() != 3 * stretches_.size() || buffer.size() % 4 != 0)
    throw swe::StateError(in.what() + " holds another sea boundary than this scene's");
  for (std::size_t k = 0; k < stretches_.size(); ++k) {
    stretches_[k].held = {held[3 * k], held[3 * k + 1], held[3 * k + 2]};
  }
  buffer_.clear();
  for (std::size_t j = 0; j < buffer.size(); j += 4) {
    buffer_.push_back({buffer[j], buffer[j + 1], buffer[j + 2], buffer[j + 3] != 0.0});
  }
  filled_ = in.count() != 0;
  added_m3_ = in.number();
  removed_m3_ = in.number();
  particles_added_ = in.count();
  particles_removed_ = in.count();
}

}  // namespace swemps::boundaries
