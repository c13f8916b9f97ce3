#include <algorithm>
#include <vector>

#include "scoped_timer.hpp"
#include "swemps/neighbors/parallel.hpp"
#include "swemps/neighbors/row_repair.hpp"
#include "swemps/swe/simulation.hpp"

// The part of the simulation that keeps the neighbour rows and the summed fields up to date:
// the sort by cell, the wall ghosts, the search of every row, its repairs around a few changed
// particles, and the depth sums over them (simulation.hpp, step 1).

namespace swemps::swe {

namespace {

// Steps between two sorts of the particles by cell: sorting costs a tenth of a step; between
// sorts, the neighbour search still finds every neighbour, only with less memory locality.
constexpr std::size_t kSortInterval = 8;

// Cells half as wide as the support for the neighbour search: about 40 candidates per
// particle instead of 57 for some 20 neighbours (neighbors/cell_list.hpp).
constexpr int kCellSubdivisions = 2;

neighbors::Coordinates<2> positions(const particles::SweParticles& p, std::size_t count) {
  return {std::span<const double>(p.x.data(), count), std::span<const double>(p.y.data(), count)};
}

}  // namespace

void Simulation::sort_by_cell() {
  ScopedTimer timer(phase_times_.sort);
  last_sort_step_ = steps_;
  sorted_count_ = particles_.fluid_count();
  // The cells the search will use, so that a row, searched block by block, comes out nearly
  // in ascending order (the order rows are kept in: neighbors/neighbor_list.hpp) and putting
  // it in order costs little.
  const std::size_t n = particles_.fluid_count();
  double radius = largest_search_radius();
  if (!scheme_->uniform_radius()) {
    // The search fills search_radii_ again after the sort.
    search_radii_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      search_radii_[i] = scheme_->search_radius(particles_.smoothing_length[i]);
    radius = typical_search_radius();
  }
  cells_.build(positions(particles_, n), radius, kCellSubdivisions);
  order_.assign(cells_.order().begin(), cells_.order().end());
  particles_.reorder(order_);
}

double Simulation::largest_search_radius() const {
  const std::size_t n = particles_.fluid_count();
  std::array<double, reduction_chunks> largest{};
  parallel_chunks(n, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      largest[chunk] = std::max(largest[chunk], particles_.smoothing_length[i]);
  });
  return scheme_->search_radius(*std::max_element(largest.begin(), largest.end()));
}

void Simulation::add_ghosts_and_neighbors() {
  const auto fluid_radii =
      std::span<const double>(particles_.smoothing_length).first(particles_.fluid_count());
  listed_smoothing_length_.assign(fluid_radii.begin(), fluid_radii.end());
  // Ghosts of every particle within the largest search radius of a wall: a particle's mirror
  // image is a neighbour of the particles near the wall whose support reaches it.
  const double reach = largest_search_radius();
  ghost_reach_ = reach;
  {
    ScopedTimer timer(phase_times_.walls);
    if (!walls_.empty()) {
      set_own_search_radii();
      walls_.add_ghosts(particles_, reach, own_search_radius_);
    }
    particles_.close_mirror_images();
    for (const std::size_t k : ghost_effects_)
      effects_[k]->add_ghosts(particles_, reach, settings_, time_s_);
  }
  search_neighbors(reach);
  if (walls_.empty()) return;
  ScopedTimer timer(phase_times_.walls);
  walls_.hide_pairs_across_walls(particles_, neighbor_list_);
}

void Simulation::search_neighbors(double reach) {
  ScopedTimer timer(phase_times_.neighbors);
  ++search_counts_.searches;
  const auto coords = positions(particles_, particles_.size());
  if (scheme_->uniform_radius()) {
    cells_.build(coords, reach, kCellSubdivisions);
    build_neighbor_list<2>(cells_, coords, particles_.fluid_count(), reach, neighbor_list_);
    return;
  }
  search_radii_.resize(particles_.size());
  parallel_for(particles_.size(), [&](std::size_t i) {
    search_radii_[i] = scheme_->search_radius(particles_.smoothing_length[i]);
  });
  // Cells for a typical radius, not the largest: a thin sheet's few wide kernels would
  // otherwise widen every particle's search (4x the candidates where the radius cap doubles
  // a radius). Those above it are found by the builder's own way for wide points.
  cells_.build(coords, typical_search_radius(), kCellSubdivisions);
  build_neighbor_list<2>(cells_, coords, search_radii_, particles_.fluid_count(), neighbor_list_);
}

// Why: a ghost beyond a second wall is placed only within its particle's own search radius
// (GhostWalls::add_ghosts); every other wall and ghost within the widest search radius of the
// scene, as a neighbour's kernel may reach that far.
void Simulation::set_own_search_radii() {
  const std::size_t n = particles_.fluid_count();
  own_search_radius_.resize(n);
  parallel_for(n, [&](std::size_t i) {
    own_search_radius_[i] = scheme_->search_radius(particles_.smoothing_length[i]);
  });
}

double Simulation::typical_search_radius() const {
  // The typical radius (neighbors::typical_radius_quantile) of the fluid particles' search
  // radii.
  const std::size_t n = particles_.fluid_count();
  if (n == 0) return largest_search_radius();
  return neighbors::typical_radius(std::span<const double>(search_radii_.data(), n),
                                   typical_scratch_);
}

// update_fields() without the radius, the sort and the sums: the ghosts and neighbour list of
// a restored state, which are functions of the saved positions, fields and radius alone.
void Simulation::rebuild_neighborhood() {
  particles_.drop_ghosts();
  if (particles_.fluid_count() == 0) return;
  // Searched with the radii the saved list was searched with (listed_smoothing_length_), then
  // the radii the sums reached, which the ghosts take with the other fields.
  std::vector<double> reached = listed_smoothing_length_;
  particles_.smoothing_length.swap(reached);
  add_ghosts_and_neighbors();
  particles_.smoothing_length.resize(particles_.fluid_count());
  particles_.smoothing_length.swap(reached);
  particles_.smoothing_length.resize(particles_.size());
  set_ghost_fields();
}

bool Simulation::sorting_due() const {
  // Particles move at most about half a spacing per step (eq 13), so memory order decays
  // slowly; a particle set that grew or shrank (splitting, inflow, outflow) is sorted at once,
  // as new particles are appended far from their neighbours in memory.
  return steps_ - last_sort_step_ >= kSortInterval || particles_.fluid_count() != sorted_count_ ||
         steps_ == 0;
}

void Simulation::update_fields(bool sort) {
  particles_.drop_ghosts();
  if (particles_.fluid_count() == 0) return;  // dry so far: nothing to sum
  // The radii from the areas of the previous summation: they must be known before the
  // neighbours (and so the new areas) can be found.
  scheme_->choose_smoothing_lengths(particles_);
  if (sort) sort_by_cell();
  // A radius that outgrew its search (the conservative scheme's depth iteration widened it
  // past the margin) needs its row searched again with the new radius (repair_outgrown_rows);
  // where that cannot be done, every row, never more than a few times, as each pass starts
  // from the radii the last one reached.
  for (;;) {
    add_ghosts_and_neighbors();
    bool summed = false;
    {
      ScopedTimer timer(phase_times_.depth);
      summed = scheme_->sum_depth(particles_, neighbor_list_);
    }
    if (summed || repair_outgrown_rows()) break;
    particles_.drop_ghosts();
  }
  finish_fields();
}

void Simulation::finish_fields() {
  neighbor_counts_.add(neighbor_list_);
  set_ghost_fields();
}

void Simulation::set_ghost_fields() {
  // The force reads the ghosts' depth, area and radius: their particles', then what the
  // boundaries other than walls set for their own.
  boundaries::GhostWalls::copy_fields_to_ghosts(particles_);
  for (const std::size_t k : ghost_effects_) effects_[k]->set_ghost_fields(particles_);
}

// Why only the outgrown rows: a wider kernel changes its own row, and another row only by
// adding the particle where the wider kernel now reaches; that row's own kernel, inside its
// search radius, does not reach so far, so no other depth changes (eq 7 sums a particle's own
// kernel). The rows are those a new search would give (neighbors/row_repair.hpp). Measured on
// the valley flood: 22 % of the searches were such second searches.
bool Simulation::repair_outgrown_rows() {
  // Each pass widens the few radii by at most the Newton steps' bound; more passes than this
  // means the radii are still moving and a new search is as cheap.
  constexpr int kRepairPasses = 4;
  if (scheme_->uniform_radius()) return false;
  const std::size_t n = particles_.fluid_count();
  for (int pass = 0; pass < kRepairPasses; ++pass) {
    // A copy: the sum below names the next pass's.
    const std::vector<std::uint32_t> grown(scheme_->outgrown().begin(), scheme_->outgrown().end());
    if (grown.empty()) return false;
    repaired_.clear();
    for (const std::uint32_t i : grown) {
      const double radius = scheme_->search_radius(particles_.smoothing_length[i]);
      // Ghosts exist only within ghost_reach_ of a wall: a wider kernel might miss some.
      if ((!walls_.empty() || !ghost_effects_.empty()) && radius > ghost_reach_) return false;
      search_radii_[i] = radius;
      listed_smoothing_length_[i] = particles_.smoothing_length[i];
      repaired_.push_back(i);
    }
    // A ghost carries its particle's radius into the search (as a new search would give it).
    for (std::size_t g = n; g < particles_.size(); ++g) {
      const std::uint32_t from = particles_.source[g];
      if (!std::binary_search(grown.begin(), grown.end(), from)) continue;
      search_radii_[g] = search_radii_[from];
      particles_.smoothing_length[g] = particles_.smoothing_length[from];
      repaired_.push_back(static_cast<std::uint32_t>(g));
    }
    std::vector<std::uint32_t> rows;
    {
      ScopedTimer timer(phase_times_.neighbors);
      ++search_counts_.repairs;
      rows = neighbors::repair_rows<2>(cells_, positions(particles_, particles_.size()),
                                       search_radii_, n, repaired_, neighbor_list_);
    }
    if (!walls_.empty()) {  // the rewritten rows, as a new search would give them
      ScopedTimer timer(phase_times_.walls);
      walls_.hide_pairs_across_walls(particles_, neighbor_list_, rows);
    }
    ScopedTimer timer(phase_times_.depth);
    if (scheme_->sum_depth_of(particles_, neighbor_list_, grown)) return true;
  }
  return false;
}

// Why: splitting changes a few particles in most steps of a spreading flood (the valley flood:
// 11,139 of its 12,359 steps), and a second search and sum of every particle for them was 36 %
// of the searches and sums.
bool Simulation::repair_after_resolution(std::size_t count_before,
                                         std::vector<std::uint32_t> changed) {
  const std::size_t n = particles_.fluid_count();
  if (!walls_.empty() || !ghost_effects_.empty() || scheme_->uniform_radius() || n < count_before ||
      particles_.ghost_count() != 0)
    return false;
  for (const auto& effect : effects_) {
    if (effect->stage() == Stage::resolution && !effect->lists_changes()) return false;
  }
  scheme_->choose_smoothing_lengths(particles_);
  for (std::size_t i = count_before; i < n; ++i) changed.push_back(static_cast<std::uint32_t>(i));
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  search_radii_.resize(n);
  listed_smoothing_length_.resize(n);
  for (const std::uint32_t i : changed) {
    search_radii_[i] = scheme_->search_radius(particles_.smoothing_length[i]);
    listed_smoothing_length_[i] = particles_.smoothing_length[i];
  }
  std::vector<std::uint32_t> rows;
  {
    ScopedTimer timer(phase_times_.neighbors);
    ++search_counts_.repairs;
    const auto coords = positions(particles_, n);
    cells_.build(coords, typical_search_radius(), kCellSubdivisions);
    rows = neighbors::repair_rows<2>(cells_, coords, search_radii_, n, changed, neighbor_list_);
  }
  // Each row summed again from the radius it was searched with, so that the scheme tells
  // whether its kernel outgrew that search (the first sum moved every radius).
  for (const std::uint32_t i : rows) particles_.smoothing_length[i] = listed_smoothing_length_[i];
  bool summed = false;
  {
    ScopedTimer timer(phase_times_.depth);
    summed = scheme_->sum_depth_of(particles_, neighbor_list_, rows);
  }
  if (!summed && !repair_outgrown_rows()) return false;
  finish_fields();
  return true;
}

}  // namespace swemps::swe
