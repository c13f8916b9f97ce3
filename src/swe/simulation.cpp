#include "swemps/swe/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "scoped_timer.hpp"
#include "swemps/neighbors/parallel.hpp"
#include "swemps/particles/resize_with_room.hpp"

namespace swemps::swe {

namespace {

// Steps between two snapshots kept for the rollback after a breakdown (keep_snapshot()).
constexpr std::size_t kSnapshotInterval = 32;

constexpr const char* kStateLabel = "swe-mps shallow-water simulation";

using Field = const std::vector<double>*;

// Whether the first n values of every field are finite (NaN fails |v| <= max as infinity
// does). In parallel over chunks, each ORing its flags without a branch, so that the loop
// vectorises and the check costs little more than reading the values once.
bool all_finite(std::initializer_list<Field> fields, std::size_t n) {
  constexpr double kLargest = std::numeric_limits<double>::max();
  std::array<std::uint8_t, reduction_chunks> broken{};
  parallel_chunks(n, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    bool bad = false;
    for (const Field field : fields) {
      const double* values = field->data();
      for (std::size_t i = begin; i < end; ++i) bad |= !(std::abs(values[i]) <= kLargest);
    }
    broken[chunk] = bad;
  });
  return std::none_of(broken.begin(), broken.end(), [](std::uint8_t b) { return b != 0; });
}

// The first particle with a non-finite value in the first field that has one: fields are
// given in the order they derive from each other, so the particle named is where the trouble
// began (a broken volume, not the depths of its neighbours that it broke). A serial scan, run
// only after all_finite() has failed, so that it names the same particle for any number of
// threads.
std::optional<std::size_t> first_broken(std::initializer_list<Field> fields, std::size_t n) {
  for (const Field field : fields) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite((*field)[i])) return i;
    }
  }
  return std::nullopt;
}

bool finite(double a, double b) { return std::isfinite(a) && std::isfinite(b); }

// "(a, b)" with enough digits to tell neighbouring particles apart.
std::string pair(double a, double b) {
  std::ostringstream out;
  out << std::setprecision(9) << '(' << a << ", " << b << ')';
  return out.str();
}

std::string number(double a) {
  std::ostringstream out;
  out << std::setprecision(9) << a;
  return out.str();
}

// What is wrong with particle i of a refreshed state, in the order the quantities derive from
// each other: a broken volume breaks the depth of every neighbour, a broken depth the area.
std::string describe_refreshed(const particles::SweParticles& p, std::size_t i) {
  const std::string particle = " of particle " + std::to_string(i);
  if (!finite(p.x[i], p.y[i]))
    return "non-finite position " + pair(p.x[i], p.y[i]) + " m" + particle;
  const std::string where = particle + " at " + pair(p.x[i], p.y[i]) + " m";
  if (!finite(p.u[i], p.v[i])) {
    return "non-finite velocity (u, v) = " + pair(p.u[i], p.v[i]) + " m/s" + where;
  }
  if (!std::isfinite(p.volume[i]))
    return "non-finite volume " + number(p.volume[i]) + " m3" + where;
  if (!std::isfinite(p.depth[i])) return "non-finite depth " + number(p.depth[i]) + " m" + where;
  return "non-finite area " + number(p.area[i]) + " m2" + where;
}

}  // namespace

Simulation::Simulation(particles::SweParticles fluid, Settings settings,
                       boundaries::GhostWalls walls, std::vector<std::unique_ptr<Effect>> effects)
    : particles_(std::move(fluid)),
      settings_(settings),
      walls_(std::move(walls)),
      effects_(std::move(effects)),
      effect_seconds_(effects_.size(), 0.0),
      scheme_(make_scheme(settings)) {
  if (particles_.fluid_count() == 0 && effects_.empty())
    throw std::invalid_argument("simulation: no water particles and nothing to add any");
  if (particles_.ghost_count() != 0)
    throw std::invalid_argument("simulation: ghosts in the initial state");
  book_initial_volumes();
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    if (effects_[k]->adds_ghosts()) ghost_effects_.push_back(k);
  }
}

void Simulation::book_initial_volumes() {
  ledger_.initial_m3 = particles_.total_fluid_volume();
  const std::size_t labels = particles_.label_count();
  ledger_.label_initial_m3.assign(labels, 0.0);
  ledger_.label_added_m3.assign(labels, 0.0);
  ledger_.label_removed_m3.assign(labels, 0.0);
  for (std::size_t k = 0; k < labels; ++k) {
    ledger_.label_initial_m3[k] = particles_.label_volume(k);
  }
}

void Simulation::start_pathline(std::size_t i, std::int32_t index) {
  if (!particles_.tracks_pathlines() || i >= particles_.fluid_count() || index < 0) {
    throw std::invalid_argument("start_pathline: particle " + std::to_string(i) +
                                " cannot carry pathline " + std::to_string(index));
  }
  particles_.pathline[i] = index;
}

std::vector<particles::PathlineEnd> Simulation::take_pathline_ends() {
  std::vector<particles::PathlineEnd> ended;
  ended.swap(particles_.pathline_ends);
  return ended;
}

double Simulation::relative_label_volume_change(std::size_t k) const {
  const double reference = ledger_.label_initial_m3[k] + ledger_.label_added_m3[k];
  if (!(reference > 0.0)) return 0.0;
  const double expected =
      ledger_.label_initial_m3[k] + ledger_.label_added_m3[k] - ledger_.label_removed_m3[k];
  return (particles_.label_volume(k) - expected) / reference;
}

// Non-finite values are found in passes the step makes anyway; values derive from one
// another, so a few stand for the rest:
//  - positions: a non-finite acceleration or velocity makes the position non-finite
//    (x += dt u), and the move loop, which reads every position it writes, tells whether all
//    are finite. Particles an effect added have not moved: the cell lists, which refuse a
//    non-finite coordinate (std::domain_error) before binning anything, check theirs.
//  - the refreshed fields, by eq 13's reduction, which refresh() computes for the next step:
//    a non-finite depth or velocity makes a particle's step 0 or NaN, and so the minimum (NaN
//    is never skipped); a non-finite volume makes the depth non-finite (eq 7 includes the self
//    term); and A = V / h cannot be infinite for a finite V, as h >= V w(0).
// Once one of these fails, a serial scan finds the first broken particle and names the
// quantity that broke first. What failing well costs is the snapshots (keep_snapshot()).
void Simulation::refresh() {
  if (fresh_) return;
  if (!moved_finite_) report_broken_positions();
  update_fields_checked(sorting_due());
  const std::size_t before = particles_.fluid_count();
  changed_.clear();
  run_effects(Stage::resolution, 0.0);
  // A resolution effect changed the particle set: the neighbour list and the sums no longer
  // describe it. Repaired around the changes, or once more whole, without the resolution
  // stage, so one step splits at most once.
  if (particles_.fluid_count() != before && !repair_after_resolution(before, changed_))
    update_fields_checked(sorting_due());
  check_refreshed_fields();
  fresh_ = true;
  keep_snapshot();
}

void Simulation::update_fields_checked(bool sort) {
  try {
    update_fields(sort);
  } catch (const std::domain_error&) {
    report_broken_positions();
    throw;  // not a position after all
  }
}

void Simulation::report_broken_positions() {
  const std::size_t n = particles_.fluid_count();
  auto& p = particles_;
  const auto broken = first_broken({&p.x, &p.y, &p.u, &p.v}, n);
  if (!broken) return;
  const std::size_t i = *broken;
  // With the numbering kept, the step's acceleration and starting position of i are known.
  const bool known = numbering_kept_ && steps_ > 0 && i < moved_count_ && i < accel_x_.size();
  std::string what;
  if (known && !finite(accel_x_[i], accel_y_[i])) {
    what = "non-finite acceleration " + pair(accel_x_[i], accel_y_[i]) + " m/s2";
  } else if (!finite(p.u[i], p.v[i])) {
    what = "non-finite velocity (u, v) = " + pair(p.u[i], p.v[i]) + " m/s";
  } else {
    what = "non-finite position " + pair(p.x[i], p.y[i]) + " m";
  }
  what += " of particle " + std::to_string(i);
  if (known) {
    what += " (at " + pair(old_x_[i], old_y_[i]) + " m when the step began)";
  } else if (finite(p.x[i], p.y[i])) {
    what += " at " + pair(p.x[i], p.y[i]) + " m";
  } else if (steps_ > 0) {
    what += " (added by an effect in this step)";
  }
  break_down(what);
}

void Simulation::check_refreshed_fields() {
  fluid_limit_ = swe::stable_time_step(particles_, settings_.gravity_m_s2, settings_.cfl);
  if (fluid_limit_.dt_s > 0.0) return;
  // NaN or 0: a non-finite value, or a step that collapsed for another reason (a negative
  // depth), which stable_time_step() reports.
  const std::size_t n = particles_.fluid_count();
  auto& p = particles_;
  const auto i = first_broken({&p.x, &p.y, &p.u, &p.v, &p.volume, &p.depth, &p.area}, n);
  if (i) break_down(describe_refreshed(p, *i) + " after the depth summation (eq 7)");
}

void Simulation::break_down(const std::string& what_happened) {
  std::ostringstream message;
  message << std::setprecision(9) << what_happened;
  if (replaying_) {
    // The replay is deterministic: the steps it repeats passed every check before.
    throw SimulationError(message.str() + " while replaying steps to the last good state", false);
  }
  if (steps_ == 0) {
    message << " in the starting state (t = " << time_s_ << " s): there is no good state to keep";
    throw SimulationError(message.str(), false);
  }
  const std::size_t step = steps_;
  message << ", in step " << step << " (t = " << time_s_ - last_dt_s_ << " s to " << time_s_
          << " s)";
  if (!roll_back()) throw SimulationError(message.str(), false);
  message << "; the simulation is back at the last good state, t = " << time_s_ << " s (step "
          << steps_ << ")";
  throw SimulationError(message.str(), true);
}

// Going back to the last good state. A copy of the state at the start of every step (10 fields
// of 8 bytes per particle, and what the effects hold) would cost 2 to 4 % of every step,
// measured at 1e5 and 1e6 particles. The step is deterministic instead (the same for any number
// of threads), so a snapshot taken every kSnapshotInterval steps and the time steps since are
// enough: restoring the snapshot and replaying all but the failed step lands bit for bit on the
// state that step started from. The snapshots cost 0.1 to 0.3 % of a step and 80 bytes per
// particle of memory; the replay, at most kSnapshotInterval - 1 steps, is paid only after a
// breakdown.
bool Simulation::roll_back() {
  if (!has_snapshot_ || steps_since_snapshot_.empty()) return false;
  const std::vector<double> replay(steps_since_snapshot_.begin(), steps_since_snapshot_.end() - 1);
  replaying_ = true;
  try {
    StateReader in(snapshot_.bytes(), "the snapshot kept for the rollback");
    load_state(in);
    steps_since_snapshot_.clear();
    for (const double dt : replay) advance(dt);
    refresh();
  } catch (...) {
    replaying_ = false;
    throw;
  }
  replaying_ = false;
  return true;
}

void Simulation::keep_snapshot() {
  if (replaying_ || (has_snapshot_ && steps_ < snapshot_step_ + kSnapshotInterval)) return;
  ScopedTimer timer(phase_times_.snapshots);
  snapshot_.clear();
  // Room for the fields and a margin for what grows between snapshots, allocated at once: grown
  // piecemeal, the buffer would end up to twice the size it needs.
  constexpr std::size_t kFields = 13;
  const std::size_t particles = particles_.fluid_count() + particles_.fluid_count() / 16;
  snapshot_.reserve(kFields * sizeof(double) * particles + 4096);
  write_state(snapshot_);
  has_snapshot_ = true;
  snapshot_step_ = steps_;
  steps_since_snapshot_.clear();
}

void Simulation::save_state(StateWriter& out) {
  refresh();
  write_state(out);
}

void Simulation::write_state(StateWriter& out) const {
  const std::size_t n = particles_.fluid_count();
  const auto& p = particles_;
  out.text(kStateLabel);
  out.number(time_s_);
  for (const std::size_t c :
       {steps_, particle_steps_, wall_reflections_, last_sort_step_, sorted_count_}) {
    out.count(c);
  }
  out.number(ledger_.initial_m3);
  out.number(ledger_.added_m3);
  out.number(ledger_.rain_m3);
  out.number(ledger_.removed_m3);
  for (const Field field : {&p.x, &p.y, &p.u, &p.v, &p.volume, &p.depth, &p.area, &p.initial_area,
                            &p.bed, &p.number_density, &p.smoothing_length, &p.omega}) {
    out.numbers(std::span<const double>(field->data(), n));
  }
  // Before the first search (or with no water) there is no list: the radii stand for it.
  const bool listed = listed_smoothing_length_.size() == n;
  out.numbers(std::span<const double>(
      listed ? listed_smoothing_length_.data() : p.smoothing_length.data(), n));
  out.count(effects_.size());
  StateWriter effect_state;
  for (const auto& effect : effects_) {
    out.text(effect->name());
    effect_state.clear();
    effect->save_state(effect_state);
    out.bytes(effect_state.bytes());
  }
  // Provenance, when the scene tracks it (docs/provenance.md); a record without it is laid
  // out as before.
  if (p.label_count() > 0) {
    out.numbers(std::span<const double>(p.label_share.data(), n * p.label_count()));
    for (const auto* books :
         {&ledger_.label_initial_m3, &ledger_.label_added_m3, &ledger_.label_removed_m3}) {
      out.numbers(*books);
    }
  }
  if (p.tracks_ages()) out.numbers(std::span<const double>(p.entry_time.data(), n));
  // Pathlines, when the scene asks for them; the indices are exact as doubles.
  if (p.tracks_pathlines()) {
    out.numbers(std::vector<double>(p.pathline.begin(), p.pathline.begin() + n));
  }
}

void Simulation::restore_state(StateReader& in) {
  load_state(in);
  // A record can be whole and still hold a broken state (one written by hand, or by a build
  // without these checks): refused here rather than found a step later.
  const auto& p = particles_;
  const std::size_t n = p.fluid_count();
  if (!all_finite({&p.x, &p.y, &p.u, &p.v, &p.volume, &p.depth, &p.area}, n)) {
    throw StateError(in.what() + " holds non-finite particle values");
  }
  // A fresh snapshot: a breakdown in the first steps after the restore goes back to here.
  has_snapshot_ = false;
  keep_snapshot();
}

void Simulation::load_state(StateReader& in) {
  in.expect(kStateLabel);
  const double time_s = in.number();
  std::array<std::uint64_t, 5> counts{};
  for (auto& c : counts) c = in.count();
  VolumeLedger ledger;
  ledger.initial_m3 = in.number();
  ledger.added_m3 = in.number();
  ledger.rain_m3 = in.number();
  ledger.removed_m3 = in.number();
  std::array<std::vector<double>, 13> fields;
  for (auto& f : fields) f = in.numbers();
  const std::size_t n = fields[0].size();
  for (const auto& f : fields) {
    if (f.size() != n)
      throw StateError(in.what() + " is damaged: particle fields differ in length");
  }
  for (const std::size_t k : {10, 12}) {
    for (const double h : fields[k]) {
      if (!(h > 0.0) || !std::isfinite(h))
        throw StateError(in.what() + " is damaged: smoothing length " + number(h));
    }
  }
  if (in.count() != effects_.size()) {
    throw StateError(in.what() + " was saved with another set of effects than this scene's");
  }
  std::vector<std::span<const std::byte>> effect_states;
  for (const auto& effect : effects_) {
    const std::string name = in.text();
    if (name != effect->name()) {
      throw StateError(in.what() + " holds the state of effect '" + name +
                       "' where this scene has '" + std::string(effect->name()) + "'");
    }
    effect_states.push_back(in.bytes());
  }

  particles::SweParticles p;
  const std::size_t labels = particles_.label_count();
  p.track_provenance(labels, particles_.tracks_ages());
  std::vector<double> label_share, entry_time;
  std::array<std::vector<double>, 3> label_books;
  if (labels > 0) {
    label_share = in.numbers();
    for (auto& books : label_books) books = in.numbers();
    if (label_share.size() != n * labels || label_books[0].size() != labels ||
        label_books[1].size() != labels || label_books[2].size() != labels) {
      throw StateError(in.what() + " holds the shares of another number of provenance labels");
    }
  }
  if (p.tracks_ages()) {
    entry_time = in.numbers();
    if (entry_time.size() != n) {
      throw StateError(in.what() + " is damaged: entry times differ in length");
    }
  }
  std::vector<std::int32_t> pathline;
  if (particles_.tracks_pathlines()) {
    p.track_pathlines();
    for (const double index : in.numbers()) {
      const bool whole = index == std::floor(index);
      if (!(index >= particles::kNoPathline && index < 2147483647.0) || !whole) {
        throw StateError(in.what() + " is damaged: pathline index " + number(index));
      }
      pathline.push_back(static_cast<std::int32_t>(index));
    }
    if (pathline.size() != n) {
      throw StateError(in.what() + " is damaged: pathline indices differ in length");
    }
  }
  const auto& [x, y, u, v, volume, depth, area, initial_area, bed, density, smoothing, omega,
               listed] = fields;
  for (std::size_t i = 0; i < n; ++i) {
    p.add_fluid(x[i], y[i], u[i], v[i], volume[i], depth[i], initial_area[i], bed[i]);
  }
  p.area = area;
  p.number_density = density;
  p.smoothing_length = smoothing;
  p.omega = omega;
  if (labels > 0) p.label_share = std::move(label_share);
  if (p.tracks_ages()) p.entry_time = std::move(entry_time);
  if (p.tracks_pathlines()) p.pathline = std::move(pathline);
  particles_ = std::move(p);
  listed_smoothing_length_ = listed;
  time_s_ = time_s;
  steps_ = counts[0];
  particle_steps_ = counts[1];
  wall_reflections_ = counts[2];
  last_sort_step_ = counts[3];
  sorted_count_ = counts[4];
  if (labels > 0) {
    ledger.label_initial_m3 = std::move(label_books[0]);
    ledger.label_added_m3 = std::move(label_books[1]);
    ledger.label_removed_m3 = std::move(label_books[2]);
  }
  ledger_ = ledger;
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    StateReader effect_in(effect_states[k],
                          in.what() + ", effect '" + std::string(effects_[k]->name()) + "'");
    effects_[k]->restore_state(effect_in);
    effect_in.expect_end();
  }
  rebuild_neighborhood();
  fluid_limit_ = swe::stable_time_step(particles_, settings_.gravity_m_s2, settings_.cfl);
  fresh_ = true;
  moved_finite_ = true;
}

VolumeBalanceReport Simulation::balance_volumes(std::vector<double> target_depth_m,
                                                double tolerance_m, int max_iterations) {
  std::size_t n = particles_.fluid_count();
  if (target_depth_m.size() != n) {
    throw std::invalid_argument("balance_volumes: one target depth per fluid particle needed");
  }
  for (const double d : target_depth_m) {
    if (!(d > 0.0) || !std::isfinite(d))
      throw std::invalid_argument("balance_volumes: target depths must be finite and > 0");
  }
  VolumeBalanceReport report;
  report.volume_before_m3 = particles_.total_fluid_volume();
  std::vector<double> permuted(n);
  for (report.iterations = 1; report.iterations <= max_iterations; ++report.iterations) {
    update_fields(true);
    // update_fields() sorted the particles: carry the targets along.
    for (std::size_t k = 0; k < n; ++k) permuted[k] = target_depth_m[order_[k]];
    target_depth_m.swap(permuted);
    report.max_depth_error_m = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      report.max_depth_error_m =
          std::max(report.max_depth_error_m, std::abs(particles_.depth[i] - target_depth_m[i]));
    }
    if (report.max_depth_error_m <= tolerance_m) break;
    // h is linear in the volumes for a fixed radius, and every weight is positive, so this
    // multiplicative update keeps volumes positive and converges where a balanced state
    // exists. The area is set to what it will be at balance, so that eq 9 takes its radius
    // from the balanced areas in the next pass.
    //
    // Where the water is thinner than what the neighbours' kernels already bring (a shore
    // particle beside deeper water), no positive volume balances and the iteration drives
    // the volume towards zero: such a particle is removed once its area falls below
    // kVanishingArea of its lattice area, and the others are balanced without it.
    constexpr double kVanishingArea = 0.5;
    std::vector<std::uint8_t> vanishing(n, 0);
    std::size_t vanished = 0;
    for (std::size_t i = 0; i < n; ++i) {
      particles_.volume[i] *= target_depth_m[i] / particles_.depth[i];
      particles_.area[i] = particles_.volume[i] / target_depth_m[i];
      if (particles_.area[i] < kVanishingArea * particles_.initial_area[i]) {
        vanishing[i] = 1;
        ++vanished;
      }
    }
    if (vanished > 0) {
      if (vanished == n)
        throw std::invalid_argument("balance_volumes: no particle can be balanced");
      particles_.drop_ghosts();
      particles_.remove(vanishing);
      std::size_t kept = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (!vanishing[i]) target_depth_m[kept++] = target_depth_m[i];
      }
      target_depth_m.resize(kept);
      n = kept;
      permuted.resize(n);
      report.removed_particles += vanished;
    }
  }
  report.iterations = std::min(report.iterations, max_iterations);
  fresh_ = false;
  has_snapshot_ = false;  // the volumes changed: the next refresh takes a new one
  book_initial_volumes();
  report.volume_after_m3 = ledger_.initial_m3;
  return report;
}

void Simulation::take_summed_areas_as_created(std::vector<std::uint8_t> which) {
  const std::size_t n = particles_.fluid_count();
  if (which.size() != n)
    throw std::invalid_argument("take_summed_areas_as_created: one flag per fluid particle needed");
  if (n == 0) return;
  // The radius cap is a multiple of A_0, so a particle whose first sum met the cap (a shore
  // particle nearly alone in a finger of the lake) sums to another area once A_0 follows it:
  // the areas are taken again until they are those their own sum gives.
  constexpr int kMaxPasses = 20;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    update_fields(true);
    bool settled = true;
    std::vector<std::uint8_t> sorted(n);
    for (std::size_t i = 0; i < n; ++i) {
      // update_fields() sorted the particles: order_[i] is the index particle i had before.
      sorted[i] = which[order_[i]];
      if (!sorted[i]) continue;
      const double before = particles_.initial_area[i];
      particles_.initial_area[i] = particles_.area[i];
      if (pass > 0 && std::abs(particles_.area[i] - before) > 1e-12 * before) settled = false;
    }
    which = std::move(sorted);
    fresh_ = false;
    if (pass > 0 && settled) break;
  }
  has_snapshot_ = false;  // the areas changed: the next refresh takes a new snapshot
}

double Simulation::stable_time_step() {
  refresh();
  TimeStepLimit limit = fluid_limit_;
  const double effects_limit = effects_time_step_limit();
  if (effects_limit < limit.dt_s) {
    limit.dt_s = effects_limit;
  } else if (particles_.fluid_count() == 0) {
    throw SimulationError(
        "no water is left and no effect adds any at t = " + std::to_string(time_s_) + " s", true);
  }
  if (particles_.fluid_count() == 0) return limit.dt_s;  // dry: only the effects limit the step
  if (!(limit.dt_s >= settings_.min_time_step_s) || !std::isfinite(limit.dt_s)) {
    const std::size_t i = limit.particle;
    std::ostringstream msg;
    msg << std::setprecision(9) << "the time step collapsed to " << limit.dt_s << " s (floor "
        << settings_.min_time_step_s << " s) for step " << steps_ + 1 << " at t = " << time_s_
        << " s, limited by particle " << i << " at " << pair(particles_.x[i], particles_.y[i])
        << " m with depth " << particles_.depth[i]
        << " m and velocity (u, v) = " << pair(particles_.u[i], particles_.v[i])
        << " m/s; the simulation stays at the last good state, t = " << time_s_ << " s (step "
        << steps_ << ")";
    throw SimulationError(msg.str(), true);
  }
  return limit.dt_s;
}

double Simulation::effects_time_step_limit() const {
  double limit = std::numeric_limits<double>::infinity();
  for (const auto& effect : effects_) {
    limit = std::min(limit, effect->time_step_limit(settings_, time_s_));
  }
  return limit;
}

void Simulation::run_effects(Stage stage, double dt_s) {
  StepContext context{particles_, neighbor_list_, scheme_->kernel(), accel_x_, accel_y_,
                      settings_,  ledger_,        time_s_, dt_s};
  if (stage == Stage::resolution) context.changed = &changed_;
  if (stage == Stage::topology) {
    context.previous_x = old_x_;
    context.previous_y = old_y_;
  }
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    if (effects_[k]->stage() != stage) continue;
    ScopedTimer timer(effect_seconds_[k]);
    effects_[k]->apply(context);
  }
}

void Simulation::advance(double dt_s) {
  refresh();
  const std::size_t n = particles_.fluid_count();
  particles::resize_with_room(accel_x_, n);
  particles::resize_with_room(accel_y_, n);
  {
    ScopedTimer timer(phase_times_.gradient);
    scheme_->surface_acceleration(particles_, neighbor_list_, settings_.gravity_m_s2, accel_x_,
                                  accel_y_);
  }
  run_effects(Stage::forces, dt_s);
  {
    ScopedTimer timer(phase_times_.integrate);
    parallel_for(n, [&](std::size_t i) {
      particles_.u[i] += dt_s * accel_x_[i];
      particles_.v[i] += dt_s * accel_y_[i];
    });
  }
  run_effects(Stage::velocity, dt_s);
  bool shifted = false;
  {
    ScopedTimer timer(phase_times_.shift);
    particles::resize_with_room(shift_x_, n);
    particles::resize_with_room(shift_y_, n);
    shifted = scheme_->regularising_shift(particles_, neighbor_list_, dt_s, shift_x_, shift_y_);
  }
  {
    ScopedTimer timer(phase_times_.integrate);
    particles::resize_with_room(old_x_, n);
    particles::resize_with_room(old_y_, n);
    // The move also tells whether every new position is finite (refresh() says why that is
    // enough): a flag per chunk, ORed without a branch. A reflection at a wall (below) keeps a
    // finite position finite.
    constexpr double kLargest = std::numeric_limits<double>::max();
    std::array<std::uint8_t, reduction_chunks> broken{};
    parallel_chunks(n, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      bool bad = false;
      for (std::size_t i = begin; i < end; ++i) {
        old_x_[i] = particles_.x[i];
        old_y_[i] = particles_.y[i];
        particles_.x[i] += dt_s * particles_.u[i] + (shifted ? shift_x_[i] : 0.0);
        particles_.y[i] += dt_s * particles_.v[i] + (shifted ? shift_y_[i] : 0.0);
        bad |= !(std::abs(particles_.x[i]) <= kLargest) | !(std::abs(particles_.y[i]) <= kLargest);
      }
      broken[chunk] = bad;
    });
    moved_finite_ = std::none_of(broken.begin(), broken.end(), [](std::uint8_t b) { return b; });
  }
  {
    ScopedTimer timer(phase_times_.walls);
    wall_reflections_ += walls_.keep_inside(particles_, old_x_, old_y_);
  }
  particles_.drop_ghosts();
  fresh_ = false;
  const double added_m3 = ledger_.added_m3, removed_m3 = ledger_.removed_m3;
  run_effects(Stage::topology, dt_s);
  // Effects that add or remove particles book the volume, so an unchanged count and ledger
  // mean the same particles in the same order (rain changes volumes in place, and every
  // particle it adds changes the count).
  numbering_kept_ = particles_.fluid_count() == n && ledger_.added_m3 == added_m3 &&
                    ledger_.removed_m3 == removed_m3;
  moved_count_ = n;
  last_dt_s_ = dt_s;
  steps_since_snapshot_.push_back(dt_s);
  time_s_ += dt_s;
  ++steps_;
  particle_steps_ += n;
}

double Simulation::relative_volume_change() const {
  // Relative to all the water the run has had, so a run that starts dry has a reference too.
  const double reference = ledger_.initial_m3 + ledger_.added_m3 + ledger_.rain_m3;
  if (reference == 0.0) return 0.0;
  return (fluid_volume() - ledger_.expected_m3()) / reference;
}

std::vector<EffectTime> Simulation::effect_times() const {
  std::vector<EffectTime> out;
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    out.push_back({std::string(effects_[k]->name()), effect_seconds_[k], effects_[k]->report()});
  }
  return out;
}

}  // namespace swemps::swe
