#pragma once
// The shallow-water MPS simulation (method.md section 1).
//
// Water is a set of particles moving in the horizontal plane. Each carries a fixed volume
// V; its depth h comes from summing its neighbours' volumes with a kernel, its area is
// A = V / h, and it accelerates down the gradient of the water surface (eq 2). How the depth
// is summed and the force taken is the Scheme's (scheme.hpp: the seed paper's eqs 5-9, or the
// conservative scheme). Walls are mirrored ghost particles. Everything else a scene may ask for
// (bed, friction, splitting, inflow, outflow) is an Effect, called at its stage.
//
// One step, and why in this order:
//  1. refresh(): the scheme chooses each particle's radius from the previous summation (the
//     seed scheme: eq 9, one for all), sort fluid particles by cell every few steps
//     (neighbours near in memory), add wall ghosts, build the neighbour list, sum depth and
//     A = V/h (a radius that outgrew its search has its own row searched again), copy them to
//     the ghosts. Then resolution-stage effects (splitting); if they changed the particles, the
//     rows around the changes repaired and those depths summed again (without walls), or all
//     of this once more. refresh() is also what output calls, so the fields written at time t
//     are those the next step uses.
//  2. dt from CFL (eq 13) on the fresh depth and area.
//  3. a = -g grad h and the scheme's dissipation, then forces-stage effects add to a.
//  4. u += dt a (symplectic Euler: the new velocity moves the particle), then velocity-stage
//     effects (semi-implicit friction acts on the updated velocity).
//  5. x += dt u; particles whose path crossed a wall are reflected back.
//  6. ghosts dropped; topology-stage effects add or remove particles.
//
// Failing well: the state a step leaves is checked for non-finite values as it is refreshed,
// before anything reads it, and a step below Settings::min_time_step_s is refused. Either way
// SimulationError is thrown with the simulation at the last good state, the state at the end
// of the last step whose values were all finite, so that the caller can still write it (see
// refresh() for how). save_state() and restore_state() carry everything the next step depends
// on, so a restored simulation continues bit for bit (checkpoints, io/checkpoint.hpp).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/swe/effect.hpp"
#include "swemps/swe/neighbor_counts.hpp"
#include "swemps/swe/operators.hpp"
#include "swemps/swe/scheme.hpp"
#include "swemps/swe/state_record.hpp"

namespace swemps::swe {

// The run cannot go on: non-finite values or a collapsing time step.
class SimulationError : public std::runtime_error {
 public:
  explicit SimulationError(const std::string& message, bool at_last_good_state = false)
      : std::runtime_error(message), at_last_good_state_(at_last_good_state) {}
  // Whether the simulation that threw holds the last good state, the state at the end of the
  // last step whose values were all finite (fresh: refresh() has nothing left to do). False
  // only when there is none: the starting state itself was broken.
  bool at_last_good_state() const { return at_last_good_state_; }

 private:
  bool at_last_good_state_;
};

struct PhaseTimes {  // wall-clock seconds spent in each part of the step
  double sort = 0.0, neighbors = 0.0, depth = 0.0, gradient = 0.0, shift = 0.0, integrate = 0.0;
  double walls = 0.0;
  // The snapshots kept for a rollback after a breakdown (the checks for non-finite values ride
  // on passes the step makes anyway).
  double snapshots = 0.0;
};

// How the neighbour rows were brought up to date over a run: searches of every row, and
// repairs of the few rows around particles that changed (neighbors/row_repair.hpp).
struct SearchCounts {
  std::size_t searches = 0, repairs = 0;
};

// What Simulation::balance_volumes() did.
struct VolumeBalanceReport {
  int iterations = 0;
  double max_depth_error_m = 0.0;  // max |h_i - target_i| after the last iteration
  double volume_before_m3 = 0.0, volume_after_m3 = 0.0;
  std::size_t removed_particles = 0;  // shore particles no positive volume could balance
};

struct EffectTime {
  std::string name;
  double seconds = 0.0;
  std::string report;  // the effect's own one-line account of what it did
};

class Simulation {
 public:
  Simulation(particles::SweParticles fluid, Settings settings, boundaries::GhostWalls walls,
             std::vector<std::unique_ptr<Effect>> effects);

  // Brings neighbour list, ghosts, depth and area up to date for the current positions, and
  // checks the state for non-finite values. Throws SimulationError for a broken state, after
  // going back to the last good one.
  void refresh();
  // Lake at rest (docs/method.md, "Water at rest over a bed"): rescales the fluid volumes so
  // that the eq 7 depth at each particle equals target_depth_m[i] (indexed like particles()
  // before the call), iterating V_i <- V_i d_i / h_i together with eq 9's radius until
  // max |h_i - d_i| <= tolerance_m. The water surface h + z_b is then level at every particle
  // and eq 6 gives exactly no force. Shore particles that no positive volume balances are
  // removed. Resets the ledger's initial volume. Call before the first step.
  VolumeBalanceReport balance_volumes(std::vector<double> target_depth_m, double tolerance_m,
                                      int max_iterations);
  // Water from terrain at rest (docs/method.md, "Lakes over the Jacksboro DEM"): the particles
  // flagged in `which` (indexed like particles() before the call) take the area their first
  // depth sum gives as the area they were created with (initial_area, A_0), which splitting,
  // merging and the radius cap measure areas against. A shore or finger particle's summed
  // area is not its lattice cell's, and measured against the cell, splitting and merging
  // fired in lakes at rest and set them moving. Call before the first step.
  void take_summed_areas_as_created(std::vector<std::uint8_t> which);
  // eq 13 on current fields; throws SimulationError if the step is below the floor or a
  // value is non-finite.
  double stable_time_step();
  // Advances by dt (at most stable_time_step()). The state it leaves is checked by the next
  // refresh(), which every reader of the state calls first.
  void advance(double dt_s);
  // Whether time() has reached target_s, to the round-off of the running sum of dt.
  bool reached(double target_s) const {
    return !(target_s - time_s_ > 1e-12 * std::max(1.0, std::abs(target_s)));
  }
  // One step at the stable time step, shortened so as to land on target_s exactly.
  void step_towards(double target_s) { advance(std::min(stable_time_step(), target_s - time_s_)); }
  // Steps until time() reaches target_s exactly (the last step is shortened), calling
  // after_step() after each step.
  template <class AfterStep>
  void advance_to(double target_s, AfterStep&& after_step) {
    while (!reached(target_s)) {
      step_towards(target_s);
      after_step();
    }
  }
  void advance_to(double target_s) {
    advance_to(target_s, [] {});
  }

  double time() const { return time_s_; }
  std::size_t steps() const { return steps_; }
  std::size_t particle_steps() const { return particle_steps_; }
  const particles::SweParticles& particles() const { return particles_; }
  // Pathlines (docs/provenance.md; the scene's particles track them): fluid particle i
  // carries pathline `index` (>= 0) from now on, through sorts, splits and merges.
  void start_pathline(std::size_t i, std::int32_t index);
  // The pathlines whose particles went since the last call (SweParticles::remove), in order.
  std::vector<particles::PathlineEnd> take_pathline_ends();
  const Scheme& scheme() const { return *scheme_; }
  // The scheme's kernel; the radii are the particles' smoothing_length.
  const ParticleKernel& kernel() const { return scheme_->kernel(); }
  // The neighbour rows of the last refresh (fluid particles only; ghosts have no row).
  const neighbors::NeighborList& neighbor_list() const { return neighbor_list_; }
  const Settings& settings() const { return settings_; }
  const VolumeLedger& ledger() const { return ledger_; }
  double fluid_volume() const { return particles_.total_fluid_volume(); }
  // (V - expected) / (V_initial + V_added): zero up to round-off when volume is conserved.
  double relative_volume_change() const;
  // The same for the water of provenance label k (particles().label_count() > 0): what the
  // particles hold of it against what came in less what left, over all that came in (0 for a
  // label that has brought no water yet).
  double relative_label_volume_change(std::size_t k) const;
  std::size_t wall_reflections() const { return wall_reflections_; }
  const PhaseTimes& phase_times() const { return phase_times_; }
  const SearchCounts& search_counts() const { return search_counts_; }
  std::vector<EffectTime> effect_times() const;
  // The scene's effects, in the order they act within their stage.
  const std::vector<std::unique_ptr<Effect>>& effects() const { return effects_; }
  // The neighbour-row lengths of every summation since this simulation was made (a restored
  // one counts from its restart: a diagnostic, not state).
  const NeighborCounts& neighbor_counts() const { return neighbor_counts_; }

  // Everything the next step depends on: the fluid particles with all their fields (their
  // radii included: the next summation starts from them), time, step count, when the
  // particles were last sorted, the volume ledger and each effect's own state. Refreshes
  // first, so the record is of a fresh state (what the next step starts from).
  void save_state(StateWriter& out);
  // Replaces the state by one save_state() wrote for a simulation built from the same scene,
  // and rebuilds the ghosts and neighbour list without summing anything anew, so that the
  // next steps are bit for bit those the saved simulation would have made. Throws StateError
  // for a record that does not fit (other effects, damaged or non-finite fields); the
  // simulation is then not fit to run on.
  void restore_state(StateReader& in);

 private:
  // refresh() without the resolution stage; `sort`: sort the particles by cell first.
  // Wall ghosts and the boundary effects' ghosts for the current radii, then the neighbour
  // list over fluid and ghosts, without the pairs that see each other through a wall.
  void add_ghosts_and_neighbors();
  // The neighbour rows of every fluid particle (ghosts among the points), within `reach`.
  void search_neighbors(double reach);
  // Each fluid particle's own search radius (own_search_radius_), for the walls' ghosts.
  void set_own_search_radii();
  // The largest search radius of the fluid particles (the scheme's, for their radii).
  double largest_search_radius() const;
  // The radius the neighbour cells are sized for (neighbors::typical_radius of search_radii_).
  double typical_search_radius() const;
  void update_fields(bool sort);
  // After a depth sum left some radii past their search (Scheme::outgrown()): their rows
  // searched again with the radius reached, and each summed again alone, a few passes at most.
  // False when only a new search of every row will do (the scheme names none, or a radius grew
  // past the reach the walls' ghosts were made for).
  bool repair_outgrown_rows();
  // After the resolution stage changed a few particles (each effect lists_changes()): their
  // rows repaired and the depths of the rows that hold them summed again. False when the
  // refresh must be redone whole, which recomputes all it touched: walls, whose ghosts would
  // move with the particles; an effect that does not list its changes; particles removed; a
  // radius that outgrew what repair_outgrown_rows() mends.
  bool repair_after_resolution(std::size_t count_before, std::vector<std::uint32_t> changed);
  // The end of every update of the fields: the neighbour counts, and the ghosts' fields.
  void finish_fields();
  // Every ghost's fields copied from its particle, then those the boundary effects set.
  void set_ghost_fields();
  // The checks of refresh(); each throws SimulationError (after a rollback) for a broken state.
  // update_fields() that turns the cell lists' refusal of a non-finite coordinate into one.
  void update_fields_checked(bool sort);
  // Names the first particle with a non-finite position or velocity and breaks down; returns
  // if there is none.
  void report_broken_positions();
  void check_refreshed_fields();
  [[noreturn]] void break_down(const std::string& what_happened);
  // Back to the last good state: the snapshot restored, then the steps since replayed. False
  // when there is no snapshot.
  bool roll_back();
  void keep_snapshot();
  // The ledger's initial volumes (per provenance label too) from the particles as they are.
  void book_initial_volumes();
  void write_state(StateWriter& out) const;
  void load_state(StateReader& in);
  void rebuild_neighborhood();
  bool sorting_due() const;
  void sort_by_cell();
  double effects_time_step_limit() const;
  void run_effects(Stage stage, double dt_s);

  particles::SweParticles particles_;
  Settings settings_;
  boundaries::GhostWalls walls_;
  std::vector<std::unique_ptr<Effect>> effects_;
  std::vector<std::size_t> ghost_effects_;  // the effects that add ghosts (Effect::adds_ghosts)
  std::vector<double> effect_seconds_;
  std::unique_ptr<Scheme> scheme_;
  std::vector<double> search_radii_;  // per particle, ghosts included (non-uniform schemes)
  // The fluid particles' radii the neighbour list was searched with. A scheme may change the
  // radii after the search (the conservative scheme's depth iteration), and the list's cells
  // and ghosts, and so the order of every sum, follow the searched radii: a restored state
  // searches with these again to continue bit for bit.
  std::vector<double> listed_smoothing_length_;
  double ghost_reach_ = 0.0;  // the largest search radius when the ghosts were added
  std::vector<double> own_search_radius_;
  std::vector<std::uint32_t> changed_;   // what the resolution stage changed (StepContext)
  std::vector<std::uint32_t> repaired_;  // repair_outgrown_rows()'s points
  neighbors::CellList<2> cells_;
  neighbors::NeighborList neighbor_list_;
  std::vector<double> accel_x_, accel_y_, old_x_, old_y_, shift_x_, shift_y_;
  mutable std::vector<double> typical_scratch_;  // typical_search_radius()'s working copy
  std::vector<std::uint32_t> order_;
  VolumeLedger ledger_;
  PhaseTimes phase_times_;
  SearchCounts search_counts_;  // a diagnostic, not state
  NeighborCounts neighbor_counts_;
  double time_s_ = 0.0;
  std::size_t steps_ = 0, particle_steps_ = 0, wall_reflections_ = 0;
  std::size_t last_sort_step_ = 0, sorted_count_ = 0;  // when the particles were last sorted
  bool fresh_ = false;
  // Since the last step: whether its move left every position finite, and whether its
  // topology stage kept the particles' numbering (nothing added or removed), so that old_x_,
  // old_y_ and the accelerations still name them.
  bool moved_finite_ = true, numbering_kept_ = true;
  TimeStepLimit fluid_limit_{0.0, 0};  // eq 13 on the fields of the last refresh
  std::size_t moved_count_ = 0;        // fluid particles the last step moved
  double last_dt_s_ = 0.0;
  // The rollback after a breakdown: a saved state, taken every few steps, and the time step of
  // every step since.
  StateWriter snapshot_;  // cleared and refilled: its memory is allocated once
  bool has_snapshot_ = false, replaying_ = false;
  std::size_t snapshot_step_ = 0;
  std::vector<double> steps_since_snapshot_;
};

}  // namespace swemps::swe
