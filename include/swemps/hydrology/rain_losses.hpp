#pragma once
// What the ground takes from the rain before the rest reaches the water (docs/rain.md,
// "Losses"). Each model works cell by cell on the rain's cells, on the rain as it falls: the
// depth a cell receives over a step goes in, the excess that runs on comes out, and what was
// taken is lost from the scene. Water that runs onto a cell from elsewhere is not taken.

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "swemps/swe/state_record.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::hydrology {

// A quantity given per cell: one value everywhere, or a map's value in the map cell holding
// each cell's centre (terrain::GriddedField::cell_value) times `scale`, in the solver's units.
struct CellParameter {
  double value = 0.0;                                // where there is no map
  std::shared_ptr<const terrain::GriddedField> map;  // null: `value` everywhere
  std::string name;                                  // for messages ("initial loss")
  double scale = 1.0;                                // the map's unit in the solver's
  double most = std::numeric_limits<double>::infinity();  // the largest value allowed
  // The value at each centre. Throws std::invalid_argument for a centre off the map, or a
  // value that is nodata, negative, above `most` or not finite, naming the parameter and the
  // place.
  std::vector<double> at(std::span<const std::array<double, 2>> centres) const;
};

class RainLoss {
 public:
  virtual ~RainLoss() = default;
  // Fixes the cells (their centres, in the rain's order) before any take().
  virtual void bind(std::span<const std::array<double, 2>> centres) = 0;
  // depth_m holds each cell's rain over a step of dt_s (m); the loss takes its part of each
  // and leaves the excess there. Returns the sum of the depths taken (m).
  virtual double take(double dt_s, std::span<double> depth_m) = 0;
  // What each cell has taken so far decides what it takes next; restore_state throws
  // swe::StateError when the record holds another number of cells.
  virtual void save_state(swe::StateWriter& out) const = 0;
  virtual void restore_state(swe::StateReader& in) = 0;
};

// Initial and continuing loss: each cell keeps its first `initial` metres of rain, then loses
// up to `continuing` (m/s) x dt of each step's.
class InitialContinuingLoss final : public RainLoss {
 public:
  InitialContinuingLoss(CellParameter initial_m, CellParameter continuing_m_s);
  void bind(std::span<const std::array<double, 2>> centres) override;
  double take(double dt_s, std::span<double> depth_m) override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

 private:
  CellParameter initial_m_, continuing_m_s_;
  std::vector<double> initial_left_m_, continuing_m_s_at_;
};

// Green-Ampt infiltration (Green & Ampt 1911; under rain, Mein & Larson 1973): the soil takes
// rain at the capacity f = K (1 + psi dtheta / F), F the depth infiltrated so far, or all of
// it while the rain is lighter than that. An initial loss (interception, depression storage)
// may take the first rain before the soil does.
struct GreenAmptSoil {
  CellParameter conductivity_m_s;  // K, the saturated hydraulic conductivity
  CellParameter suction_m;         // psi, the suction head at the wetting front
  CellParameter moisture_deficit;  // dtheta, effective porosity x (1 - initial saturation)
};

class GreenAmptLoss final : public RainLoss {
 public:
  GreenAmptLoss(GreenAmptSoil soil, CellParameter initial_m);
  void bind(std::span<const std::array<double, 2>> centres) override;
  double take(double dt_s, std::span<double> depth_m) override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

  std::span<const double> infiltrated_m() const { return infiltrated_m_; }  // F per cell

 private:
  GreenAmptSoil soil_;
  CellParameter initial_m_;
  std::vector<double> conductivity_, storage_, initial_left_m_, infiltrated_m_;
};

// The depth one cell infiltrates under `rain_m` of rain falling evenly over dt_s, with
// conductivity K (m/s) and storage S = psi dtheta (m); `infiltrated_m` (F) is advanced. Exact
// for the Green-Ampt model: before ponding all the rain soaks in; ponding begins when F
// reaches K S / (i - K) for a rate i > K; once ponded, F follows the integrated Green-Ampt
// equation F2 - F1 - S ln((F2 + S) / (F1 + S)) = K t (Chow, Maidment & Mays 1988, Applied
// Hydrology, sections 4.3 and 4.4).
double green_ampt_infiltration(double conductivity_m_s, double storage_m, double rain_m,
                               double dt_s, double& infiltrated_m);

}  // namespace swemps::hydrology
