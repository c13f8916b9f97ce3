#include "swemps/scenario/memory_check.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "swemps/particles/seeding.hpp"

namespace swemps::scenario {

namespace {

// Three significant digits: enough to compare a need with what the machine has.
std::string short_number(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

std::string whole(double v) { return std::to_string(std::llround(v)); }

// A count of particles or cells: whole up to ten million, where every digit is read; three
// significant digits above, where only the size matters.
std::string count_text(double v) { return v <= 1e7 ? whole(v) : short_number(v); }

std::vector<Point> corners(const Rectangle& r) {
  return {{r.x_min, r.y_min}, {r.x_max, r.y_min}, {r.x_max, r.y_max}, {r.x_min, r.y_max}};
}

// The share of a need that one key asks for; the largest names the key in the message.
struct Share {
  double bytes = 0.0;
  std::string json_path, words;
};

void keep_largest(MemoryNeed& need, Share& largest, Share candidate) {
  if (candidate.bytes <= largest.bytes) return;
  largest = std::move(candidate);
  need.json_path = largest.json_path;
  need.largest_share = largest.words;
}

Share grid_share(const Scenario& scene, const Terrain& terrain, double& cells) {
  const swe::RegularGrid grid = output_grid(scene, terrain);
  cells = static_cast<double>(grid.nx) * static_cast<double>(grid.ny);
  return {cells * bytes_per_grid_cell(scene.output.depth_thresholds_m.size()), "/output/grid",
          count_text(cells) + " cells of the output grid (" + short_number(grid.dx) + " m x " +
              short_number(grid.dy) + " m)"};
}

// The tightest of the limits the control groups of this process set, in bytes; none: the
// largest integer. cgroup v2 names the group as "0::<path>", v1 as "<id>:memory:<path>"
// (controllers may be listed together); inside a container's own namespace the path is "/"
// and the file is at the root of the hierarchy, so both places are read.
std::uint64_t cgroup_limit_bytes() {
  std::uint64_t limit = std::numeric_limits<std::uint64_t>::max();
  const auto read_limit = [&](const std::string& file) {
    std::ifstream in(file);
    std::uint64_t value = 0;
    if (in >> value && value > 0) limit = std::min(limit, value);  // "max" reads as nothing
  };
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    const auto first = line.find(':');
    const auto second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    if (controllers.empty()) {
      read_limit("/sys/fs/cgroup" + path + "/memory.max");
      read_limit("/sys/fs/cgroup/memory.max");
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      read_limit("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes");
      read_limit("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    }
  }
  return limit;
}

}  // namespace

std::string bytes_text(double bytes) {
  static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  std::size_t unit = 0;
  while (bytes >= 1000.0 && unit + 1 < std::size(units)) {
    bytes /= 1000.0;
    ++unit;
  }
  return short_number(bytes) + " " + units[unit];
}

MemoryNeed swe_memory_need(const Scenario& scene, const Terrain& terrain) {
  MemoryNeed need;
  need.bytes_per_cell = bytes_per_grid_cell(scene.output.depth_thresholds_m.size());
  Share largest;
  for (std::size_t i = 0; i < scene.water.size(); ++i) {
    const WaterBody& body = scene.water[i];
    const auto polygon = body.polygon.empty() ? corners(terrain.domain) : body.polygon;
    // The lattice has one point per spacing^2 of the shape, to within its outline.
    const double points = particles::polygon_area(polygon) / (body.spacing_m * body.spacing_m);
    need.particles += points;
    const std::string body_path = "/water/" + std::to_string(i);
    keep_largest(need, largest,
                 {points * kBytesPerParticle, body_path + "/spacing",
                  count_text(points) + " particles of " + body_path + " at a spacing of " +
                      short_number(body.spacing_m) + " m"});
  }
  need.peak_particles = need.particles;
  if (scene.splitting) {
    const auto cap = static_cast<double>(scene.splitting->max_particles);
    need.peak_particles =
        cap > 0.0 ? std::max(need.particles, cap) : kSplittingGrowth * need.particles;
  }
  keep_largest(need, largest, grid_share(scene, terrain, need.grid_cells));
  return need;
}

template <int Dim>
MemoryNeed ns_memory_need(const Scenario& scene, const ns::TankSpec<Dim>& tank) {
  MemoryNeed need;
  need.bytes_per_cell = bytes_per_grid_cell(scene.output.depth_thresholds_m.size());
  // Nodes along each axis: the interior's, and with the solid layers behind the walls (on both
  // sides across, below only along the vertical: the tank has no lid).
  double interior_nodes = 1.0, box_nodes = 1.0;
  for (int d = 0; d < Dim; ++d) {
    const double n = (tank.interior.upper[d] - tank.interior.lower[d]) / tank.spacing_m;
    interior_nodes *= n;
    box_nodes *= n + (d == Dim - 1 ? 1.0 : 2.0) * tank.solid_layers;
  }
  double fluid = 0.0;
  for (const auto& box : tank.water) {
    double nodes = 1.0;
    for (int d = 0; d < Dim; ++d) nodes *= (box.upper[d] - box.lower[d]) / tank.spacing_m;
    fluid += nodes;
  }
  need.particles = fluid + (box_nodes - interior_nodes);
  need.peak_particles = need.particles;
  need.json_path = "/ns/spacing";
  need.largest_share = count_text(fluid) + " fluid and " + count_text(box_nodes - interior_nodes) +
                       " wall and dummy particles at a spacing of " + short_number(tank.spacing_m) +
                       " m";
  Terrain plan;
  plan.domain = scene.domain;
  double cells = 0.0;
  Share grid = grid_share(scene, plan, cells);
  need.grid_cells = cells;
  if (grid.bytes > need.particles * kBytesPerParticle) {
    need.json_path = grid.json_path;
    need.largest_share = grid.words;
  }
  return need;
}

std::uint64_t usable_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  const std::uint64_t physical =
      static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
  std::uint64_t usable = std::min(physical, cgroup_limit_bytes());
  // A cap on the address space (ulimit -v) fails allocations beyond it just the same.
  rlimit address_space{};
  if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY) {
    usable = std::min<std::uint64_t>(usable, address_space.rlim_cur);
  }
  return usable;
}

void check_fits_in_memory(const MemoryNeed& need, std::uint64_t usable_bytes) {
  if (usable_bytes == 0 || need.bytes() <= static_cast<double>(usable_bytes)) return;
  std::string particles = count_text(need.particles) + " particles";
  if (need.peak_particles > need.particles) {
    particles += " (" + count_text(need.peak_particles) + " with splitting's headroom)";
  }
  throw ScenarioError(
      need.json_path,
      "a scene of about " + particles + " and " + count_text(need.grid_cells) +
          " output grid cells, needing about " + bytes_text(need.bytes()) + " at " +
          whole(kBytesPerParticle) + " bytes per particle and " + whole(need.bytes_per_cell) +
          " per cell; most of it for " + need.largest_share,
      "a scene that fits in the " + bytes_text(static_cast<double>(usable_bytes)) +
          " of memory swe-mps may use here (a coarser spacing, less water or a coarser output "
          "grid)");
}

template MemoryNeed ns_memory_need<2>(const Scenario&, const ns::TankSpec<2>&);
template MemoryNeed ns_memory_need<3>(const Scenario&, const ns::TankSpec<3>&);

}  // namespace swemps::scenario
