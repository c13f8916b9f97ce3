#pragma once
// Rain on the terrain: water that falls on the domain from above, at a rate that may vary in
// time and space, over the whole domain or a polygon of it (docs/rain.md).
//
// The rain falls on a lattice of cells over the domain, about one particle spacing l on a
// side (the domain's width and height divided into whole numbers of cells, so that the cells
// tile the domain exactly; a polygon keeps the cells whose centres lie inside it). Each step
// [t, t + dt], after the particles have moved:
//  1. every cell receives the depth of rain its rate gives over the step, integrated exactly
//     (RainRate); the losses take their part first (below);
//  2. a cell is wet when it lies under a particle: within sqrt(A_i) of particle i, A_i its
//     area, or holding its centre. sqrt(A_i) reaches the corners of a square lattice's cells
//     (at 0.71 of it) with room to spare, so water in which particles have moved apart a
//     little still counts as wet. A wet cell's rain, and the rain it gathered while it was dry,
//     goes to the particles over it in equal shares: it raises their volumes, and, falling
//     with no horizontal momentum, lowers their velocities so that each keeps its momentum;
//  3. a dry cell gathers its rain until it holds creation_depth_m; then a particle of that
//     water (its whole gathering, at least creation_depth_m x the cell's area) is created at
//     the cell's centre, at rest, with the cell's area as the area it was created with (A_0).
//     So rain never makes a particle finer than the cell, about the scene's spacing, nor
//     thinner than creation_depth_m. The remainder, rain gathered in dry cells that never
//     reached the threshold, stays pending: pending_volume() reports it and the ledger does
//     not hold it (it is water on the ground too thin to move, a depression storage).
// Every volume that reaches a particle is booked in VolumeLedger::rain_m3, so that the
// fallen rain = the rain booked + the losses + the pending water, to round-off.
//
// Losses (hydrology/rain_losses.hpp) take their part of each cell's rain as it falls, before
// step 2; what they take never becomes water in the domain and is counted in volume_lost().
// Where and how hard the rain falls is a RainRate (hydrology/rain_rate.hpp): one series for
// every cell, or maps of the rate.
//
// The caller gives cells that lie on the ground of the domain: a polygon leaves out the parts
// walls close off, and the rain does not look for walls, except that it falls on no
// building's footprint (RainSettings::roofs).

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "swemps/boundaries/domain_outflow.hpp"
#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/hydrology/rain_losses.hpp"
#include "swemps/hydrology/rain_rate.hpp"
#include "swemps/swe/bed.hpp"
#include "swemps/swe/effect.hpp"
#include "swemps/terrain/footprints.hpp"

namespace swemps::hydrology {

// mm/h in m/s: the unit rain rates are given in, and the one the solver works in.
constexpr double kMetresPerSecondPerMmPerHour = 1e-3 / 3600.0;

struct RainSettings {
  std::string name = "rain";  // for reports
  std::uint32_t label = 0;    // the provenance label of its water (docs/provenance.md)
  boundaries::Box domain{};   // the cells tile this box
  double spacing_m = 0.0;     // l: about the side of a cell
  // The rain falls on the cells whose centres lie inside this polygon (>= 3 vertices);
  // empty: on the whole domain.
  std::vector<std::array<double, 2>> polygon;
  // Footprints of buildings that are walls (null: none): cells whose centres lie under one
  // get no rain. The walls close them off from the water, and a roof's drainage is not part
  // of the scene: its rain is not counted as fallen (docs/buildings.md).
  std::shared_ptr<const terrain::Footprints> roofs;
  // The depth a dry cell gathers before its water becomes a particle (m).
  double creation_depth_m = kDefaultCreationDepthM;
  std::shared_ptr<const swe::BedSource> bed;  // z_b of new particles; null: z_b = 0
  // One millimetre: three decades above splitting's film floor, so a new particle is split
  // like any other water, and a tenth of the wet depth maps count from, so that rain shows on
  // a map only once it has run together. At 10 mm/h a dry cell makes its particle in 6 min.
  static constexpr double kDefaultCreationDepthM = 1e-3;
};

class Rain final : public swe::Effect {
 public:
  // `rate`: where and how hard the rain falls; `losses`: what the ground takes (null: none).
  // Both are bound to the rain's cells here. Throws std::invalid_argument for a box or
  // spacing that is not positive and finite, a polygon of fewer than 3 vertices or holding no
  // cell centre, a creation depth that is not positive, an empty name, or a rate or loss that
  // cannot be had at a cell (off its map, nodata, negative).
  Rain(RainSettings settings, std::unique_ptr<RainRate> rate,
       std::unique_ptr<RainLoss> losses = nullptr);
  // The same rain at one rate over every cell, following `rate_m_s` (m/s) in time.
  Rain(RainSettings settings, boundaries::Hydrograph rate_m_s,
       std::unique_ptr<RainLoss> losses = nullptr);

  std::string_view name() const override { return settings_.name; }
  swe::Stage stage() const override { return swe::Stage::topology; }
  void apply(swe::StepContext& context) override;
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;
  // While the domain is dry nothing else limits the step: the step is kept short enough for
  // the peak rate to fill a dry cell to the creation depth no more than once, so that new
  // particles are made at about that depth and at about the time they are due.
  double time_step_limit(const swe::Settings& settings, double time_s) const override;

  std::size_t cell_count() const { return cells_.size(); }  // cells the rain falls on
  double cell_area_m2() const { return cell_dx_ * cell_dy_; }
  double rain_area_m2() const { return cell_area_m2() * static_cast<double>(cells_.size()); }
  std::array<double, 2> cell_centre(std::size_t k) const;
  const RainRate& rate() const { return *rate_; }
  // The volume of rain (m^3) that falls on the cells over [t0, t1], before losses.
  double volume_due(double t0_s, double t1_s) const;

  double volume_fallen() const { return fallen_m3_; }  // m^3, all the rain so far
  double volume_lost() const { return lost_m3_; }      // m^3, taken by the losses
  double volume_added() const { return added_m3_; }    // m^3, booked in the ledger
  double pending_volume() const;                       // m^3, gathered in dry cells
  std::size_t particles_created() const { return created_; }

 private:
  // Appends to `out` the cells a particle at (x, y) of `area` covers (see the header comment),
  // as indices into cells_.
  void covered_cells(double x, double y, double area, std::vector<std::uint32_t>& out) const;
  // The index into cells_ of the cell holding (x, y), or -1 when it is not a rain cell.
  std::int64_t cell_at(double x, double y) const;

  RainSettings settings_;
  std::unique_ptr<RainRate> rate_;
  std::unique_ptr<RainLoss> losses_;
  double cell_dx_ = 0.0, cell_dy_ = 0.0;
  std::size_t nx_ = 0, ny_ = 0;
  // Rain cells as lattice indices j * nx_ + i, ascending; the lattice's cells map back to them
  // (-1: no rain falls there).
  std::vector<std::uint32_t> cells_;
  std::vector<std::int32_t> rain_cell_of_;
  // Per rain cell: the depth gathered while dry (m); scratch for a step's rain on it (m).
  std::vector<double> pending_m_, step_rain_m_;
  // Scratch for a step: per rain cell the particles over it and its share for each (m^3);
  // per particle the cells it covers, all in one array, particle i's from covered_start_[i].
  std::vector<std::uint32_t> over_count_;
  std::vector<double> share_m3_;
  std::vector<std::uint32_t> covered_;
  std::vector<std::size_t> covered_start_;
  double fallen_m3_ = 0.0, lost_m3_ = 0.0, added_m3_ = 0.0;
  std::size_t created_ = 0;
};

}  // namespace swemps::hydrology
