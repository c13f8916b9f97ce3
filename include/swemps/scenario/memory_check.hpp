#pragma once
// Refusing a scene that cannot fit in memory before anything big is allocated. The particles
// and output grid cells a scene asks for are counted from its shapes and spacings, priced at a
// conservative cost per item, and compared with the memory of the machine. Without this a
// spacing a few times too fine ends in std::bad_alloc, or in the kernel's out-of-memory killer
// minutes into seeding.

#include <cstdint>
#include <string>

#include "swemps/ns/tank.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

// What each item is assumed to cost, kept well above what runs measure so that a refused scene
// surely would not fit (docs/performance.md). A shallow-water particle measured 259 bytes at
// 1e6 particles at the start of a run; its neighbour list grows by 4 bytes per neighbour, to
// about 470 bytes once the support has grown to 80 neighbours. A Navier-Stokes particle (fluid,
// wall or dummy, with its rows of the Poisson matrix and the preconditioner) measured about
// 500 bytes in 3D (the Martin-Moyce tank at l0 = a/40, 210,000 particles, peak resident memory
// less that of a run refused at once). 1 kB, the project's memory target per particle, covers
// both.
inline constexpr double kBytesPerParticle = 1000.0;
// A grid cell holds the gridded depth and velocity (3 doubles), the bed, the flood statistics
// (8 maps, and arrival and duration at the wet depth and at each further depth threshold), the
// maps' masked copies (3) and the single-precision buffer they are written through: counted as
// 16 doubles and 2 a threshold (208 bytes with the 4 default thresholds).
inline double bytes_per_grid_cell(std::size_t further_thresholds) {
  return 8.0 * (16.0 + 2.0 * static_cast<double>(further_thresholds + 1));
}
// Splitting without a cap is assumed to double the particles at most (the benchmark's dam
// break, docs/performance.md, grew from 1e4 to 2.1e4-2.6e4 before its front left the domain).
inline constexpr double kSplittingGrowth = 2.0;

// What a scene asks for, before any of it is allocated.
struct MemoryNeed {
  double particles = 0.0;       // at the start (water inflows bring in later is not counted)
  double peak_particles = 0.0;  // with the headroom splitting may take
  double grid_cells = 0.0;      // of the output grid
  double bytes_per_cell = bytes_per_grid_cell(4);  // with the scene's depth thresholds
  // The key whose value asks for the largest share, and that share in words ("1.2e9 particles
  // of /water/0 at a spacing of 0.01 m"): where a user would change the scene.
  std::string json_path;
  std::string largest_share;

  double bytes() const { return peak_particles * kBytesPerParticle + grid_cells * bytes_per_cell; }
};

// A shallow-water scene once its rasters are read (the domain and the raster grid may come
// from them): the lattice points of every water body, with depth or not (a lake filled over
// the terrain or a depth raster may leave some dry, so this is an upper count), and the output
// grid's cells.
MemoryNeed swe_memory_need(const Scenario& scene, const Terrain& terrain);

// A Navier-Stokes scene: the tank's fluid nodes and its wall and dummy layers, and the output
// grid's cells.
template <int Dim>
MemoryNeed ns_memory_need(const Scenario& scene, const ns::TankSpec<Dim>& tank);

// The memory this process may use, in bytes: the machine's physical memory, or less where a
// control group (a container's limit) or an address-space limit (ulimit -v) caps it. 0 when it
// cannot be found out.
std::uint64_t usable_memory_bytes();

// Throws ScenarioError at need.json_path when the need exceeds `usable_bytes`, saying how many
// particles and bytes the scene needs and how much there is. Usable bytes of 0
// (unknown) pass.
void check_fits_in_memory(const MemoryNeed& need, std::uint64_t usable_bytes);

// "23.5 GB": bytes in decimal units, three significant digits.
std::string bytes_text(double bytes);

extern template MemoryNeed ns_memory_need<2>(const Scenario&, const ns::TankSpec<2>&);
extern template MemoryNeed ns_memory_need<3>(const Scenario&, const ns::TankSpec<3>&);

}  // namespace swemps::scenario
