#pragma once
// An effect is one physical or numerical process a scene asks for (bed slope, friction,
// splitting, inflow, outflow ...): one small class with one job. The simulation holds only
// the effects its scene asked for and calls each at its stage of the step; the step loop
// itself never asks whether an effect is enabled, so an absent effect costs nothing.

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/particle_kernel.hpp"
#include "swemps/swe/settings.hpp"
#include "swemps/swe/state_record.hpp"

namespace swemps::swe {

// Volume accounting: what the run started with, what effects added and removed.
struct VolumeLedger {
  double initial_m3 = 0.0;
  double added_m3 = 0.0;    // e.g. inflow
  double rain_m3 = 0.0;     // rain that reached the water (after its losses)
  double removed_m3 = 0.0;  // e.g. outflow, particles leaving the domain
  double expected_m3() const { return initial_m3 + added_m3 + rain_m3 - removed_m3; }

  // The same per provenance label (SweParticles::label_share), when the particles track it;
  // empty otherwise. A label's water comes in once, from its one kind of source (added counts
  // inflow and rain alike), and leaves wherever the water goes.
  std::vector<double> label_initial_m3, label_added_m3, label_removed_m3;
  // Books `m3` of new water of label k (nothing when labels are not tracked).
  void add_to_label(std::size_t k, double m3) {
    if (!label_added_m3.empty()) label_added_m3[k] += m3;
  }
  // Books fluid particle i of `p` as removed, share by share.
  void remove_labelled(const particles::SweParticles& p, std::size_t i) {
    const std::size_t labels = label_removed_m3.size();
    for (std::size_t k = 0; k < labels; ++k) {
      label_removed_m3[k] += p.volume[i] * p.label_share[i * labels + k];
    }
  }
};

// Where in the step an effect acts (the step order is documented in simulation.hpp).
enum class Stage {
  resolution,  // in refresh(), after the depth summation, ghosts present: may replace and add
               // particles (splitting); the simulation then repairs the neighbours and depths
               // around what changed (Effect::lists_changes), or redoes the refresh once
  forces,      // after the depth-gradient acceleration: add accelerations (bed slope ...)
  velocity,    // after the velocity update, before the move (semi-implicit friction ...)
  topology,    // after the move, ghosts dropped: add or remove particles (outflow, inflow)
};

struct StepContext {
  particles::SweParticles& particles;
  const neighbors::NeighborList& neighbors;  // valid in the resolution, forces and velocity stages
  // The scheme's kernel: pair weights from the particles' own radii (smoothing_length).
  const ParticleKernel& kernel;
  // m s^-2, fluid particles: the forces stage adds to them; the velocity stage reads the
  // step's acceleration in them (friction takes the speed the step started with).
  std::span<double> accel_x, accel_y;
  const Settings& settings;
  VolumeLedger& ledger;
  double time_s;  // at the start of the step
  double dt_s;    // 0 in the resolution stage (the step is not yet chosen)
  // Fluid positions before this step's move, indexed like the particles as the topology
  // stage begins (empty in other stages). An effect that removes particles invalidates them
  // for the effects after it, so effects that read them come first in the topology stage.
  std::span<const double> previous_x = {}, previous_y = {};
  // Resolution stage: an effect that says lists_changes() appends here every fluid particle it
  // moves or changes in place (volume, radius, A_0); the particles it appends count as changed
  // without being listed. Null in other stages.
  std::vector<std::uint32_t>* changed = nullptr;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string_view name() const = 0;
  virtual Stage stage() const = 0;
  virtual void apply(StepContext& context) = 0;
  // The longest step this effect allows at time_s (s): an inflow limits the step by eq 13
  // applied to the water it is about to let in, which matters most while the domain is dry.
  virtual double time_step_limit(const Settings& /*settings*/, double /*time_s*/) const {
    return std::numeric_limits<double>::infinity();
  }
  // Whether, in the resolution stage, the effect lists in StepContext::changed every particle
  // it moves or changes in place, and neither removes nor reorders any: the simulation then
  // repairs the neighbours and depths around those alone instead of searching and summing
  // every particle again.
  virtual bool lists_changes() const { return false; }
  // Boundary ghosts: an effect that owns a stretch of boundary other than a wall (an open sea
  // edge) says so here, and the simulation calls the two hooks below in every refresh, beside
  // the walls' ghosts. Effects that say false are never called, so they cost nothing.
  virtual bool adds_ghosts() const { return false; }
  // Appends the ghosts that stand for the water beyond the boundary, as deep as `reach` (m),
  // after the walls' ghosts and before the neighbour search (SweParticles::add_ghost: each
  // names a fluid particle whose radius it takes; its position, velocity and volume, the
  // water it brings to its neighbours' depth sums, are the effect's). time_s is the start of
  // the coming step.
  virtual void add_ghosts(particles::SweParticles& /*p*/, double /*reach_m*/,
                          const Settings& /*settings*/, double /*time_s*/) {}
  // After the depth summation and the copy of every ghost's fields from its particle: sets
  // the fields of the ghosts this effect added (depth, area ...).
  virtual void set_ghost_fields(particles::SweParticles& /*p*/) {}
  // One line for the closing summary (what the effect did over the run); empty for none.
  virtual std::string report() const { return {}; }
  // What the effect carries from one step to the next (an inflow's progress, a time-step
  // limit found in the last step, the counts of its report), for checkpoints and for the
  // rollback after a breakdown: after restore_state() of what save_state() wrote, the effect
  // must make exactly the steps it would have made. An effect without such state keeps these.
  virtual void save_state(StateWriter& /*out*/) const {}
  virtual void restore_state(StateReader& /*in*/) {}
};

}  // namespace swemps::swe
