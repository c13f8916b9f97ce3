#include "swemps/scenario/build.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "boundary_effects.hpp"
#include "buildings.hpp"
#include "hydrology_effects.hpp"
#include "rain_maps.hpp"
#include "scene_crs.hpp"
#include "starting_surface.hpp"
#include "swemps/boundaries/domain_outflow.hpp"
#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/io/geographic.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/particles/seeding.hpp"
#include "swemps/scenario/memory_check.hpp"
#include "swemps/splitting/particle_merging.hpp"
#include "swemps/splitting/particle_splitting.hpp"
#include "swemps/swe/balanced_bed_slope.hpp"
#include "swemps/swe/bed_slope.hpp"
#include "swemps/swe/conservative_scheme.hpp"
#include "swemps/swe/eddy_viscosity.hpp"
#include "swemps/swe/manning_friction.hpp"
#include "swemps/swe/shock_viscosity.hpp"

namespace swemps::scenario {

namespace {

using Field = terrain::GriddedField;
using FieldPtr = std::shared_ptr<const Field>;

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string fmt_point(double x, double y) { return "(" + fmt(x) + ", " + fmt(y) + ")"; }

std::string describe_box(const Rectangle& r) {
  return "[" + fmt(r.x_min) + ", " + fmt(r.x_max) + "] x [" + fmt(r.y_min) + ", " + fmt(r.y_max) +
         "]";
}

std::string index_path(const std::string& array, std::size_t i) {
  return array + "/" + std::to_string(i);
}

Rectangle extent(const Field& field) {
  const auto& g = field.geometry();
  return {g.x_left, g.x_right(), g.y_bottom(), g.y_top};
}

bool lies_on(const Rectangle& inner, const Rectangle& outer) {
  const double slack = slack_for(outer);
  return inner.x_min >= outer.x_min - slack && inner.x_max <= outer.x_max + slack &&
         inner.y_min >= outer.y_min - slack && inner.y_max <= outer.y_max + slack;
}

std::vector<Point> corners(const Rectangle& r) {
  return {{r.x_min, r.y_min}, {r.x_max, r.y_min}, {r.x_max, r.y_max}, {r.x_min, r.y_max}};
}

// ---------------------------------------------------------------------------------------------
// Rasters

std::string nodata_cells(std::size_t count) {
  return std::to_string(count) + (count == 1 ? " nodata cell" : " nodata cells");
}

// A raster the solver samples everywhere in the domain must cover it without gaps.
void check_covers(const Field& field, const Rectangle& domain, const std::string& json_path,
                  const std::string& what) {
  if (!lies_on(domain, extent(field))) {
    throw ScenarioError(json_path,
                        what + " covering " + describe_box(extent(field)) +
                            ", which does not hold the domain " + describe_box(domain),
                        "a raster covering the whole domain");
  }
  const auto nodata = field.nodata_in(domain.x_min, domain.x_max, domain.y_min, domain.y_max);
  if (nodata.count > 0) {
    throw ScenarioError(json_path,
                        what + " with " + nodata_cells(nodata.count) +
                            " inside the domain, the first centred at " +
                            fmt_point(nodata.x_m, nodata.y_m),
                        "no nodata inside the domain: shrink the domain to avoid them, or fill "
                        "the raster's gaps");
  }
}

// The centre and value (x, y, v) of the first cell, in row-major order, whose value `pick`
// takes among the cells centred within one cell of `r`: those bilinear sampling may reach from
// inside it.
template <class Pick>
std::optional<std::array<double, 3>> first_cell_near(const Field& field, const Rectangle& r,
                                                     const Pick& pick) {
  const auto& g = field.geometry();
  for (std::size_t row = 0; row < g.rows; ++row) {
    const double y = g.cell_centre_y(row);
    if (y < r.y_min - g.cell_height || y > r.y_max + g.cell_height) continue;
    for (std::size_t col = 0; col < g.columns; ++col) {
      const double x = g.cell_centre_x(col);
      if (x < r.x_min - g.cell_width || x > r.x_max + g.cell_width) continue;
      const double v = field.at(col, row);
      if (pick(v)) return std::array<double, 3>{x, y, v};
    }
  }
  return std::nullopt;
}

// Manning's n must be > 0 wherever the interpolation may reach from inside the domain.
void check_positive(const Field& field, const Rectangle& domain, const std::string& json_path) {
  const auto bad =
      first_cell_near(field, domain, [](double n) { return !std::isnan(n) && !(n > 0.0); });
  if (!bad) return;
  const auto [x, y, n] = *bad;
  throw ScenarioError(json_path,
                      "Manning's n = " + fmt(n) + " in the cell centred at " + fmt_point(x, y),
                      "values > 0 (s m^-1/3) over the domain");
}

// The Manning's n of each cell of a land-use raster from its class's entry in `table`. Every
// class the friction may sample from inside the domain (cells within one cell of it) must be in
// the table; classes beyond it, which the friction never samples, take the table's first n, so
// that no class the water cannot reach needs an entry.
Field roughness_of_land_use(const Field& classes, const std::map<long long, double>& table,
                            const Rectangle& domain, const std::string& json_path) {
  const auto missing = first_cell_near(classes, domain, [&](double c) {
    return !std::isnan(c) && (c != std::round(c) || !table.contains(std::llround(c)));
  });
  if (missing) {
    const auto [x, y, c] = *missing;
    std::string known;
    for (const auto& [code, n] : table) known += (known.empty() ? "" : ", ") + std::to_string(code);
    throw ScenarioError(
        json_path,
        "the land-use class " + fmt(c) + " in the cell centred at " + fmt_point(x, y) +
            ", which /friction/land_use_manning_n does not list",
        "a Manning's n for every class over the domain (the table lists " + known + ")");
  }
  std::vector<double> n(classes.values().size(), std::numeric_limits<double>::quiet_NaN());
  const double fallback = table.begin()->second;
  for (std::size_t k = 0; k < n.size(); ++k) {
    const double c = classes.values()[k];
    if (std::isnan(c) || c != std::round(c)) continue;
    const auto it = table.find(std::llround(c));
    n[k] = it != table.end() ? it->second : fallback;
  }
  return Field(classes.geometry(), std::move(n), classes.crs_wkt(), "Manning's n of land use");
}

// A raster of a starting disturbance (a surface's rise, a velocity component) need not cover
// the domain, as water without a disturbance is still; but one that misses it entirely is a
// mistake (another CRS, another place), and so is one with no value over it.
void check_overlaps(const Field& field, const Rectangle& domain, const std::string& json_path,
                    const std::string& what) {
  const Rectangle e = extent(field);
  const Rectangle overlap{std::max(e.x_min, domain.x_min), std::min(e.x_max, domain.x_max),
                          std::max(e.y_min, domain.y_min), std::min(e.y_max, domain.y_max)};
  if (!(overlap.x_min < overlap.x_max && overlap.y_min < overlap.y_max)) {
    throw ScenarioError(
        json_path,
        what + " covering " + describe_box(e) + ", which misses the domain " + describe_box(domain),
        "a raster over the domain, in the scene's CRS or with one GDAL can warp");
  }
  if (first_cell_near(field, overlap, [](double v) { return !std::isnan(v); })) return;
  throw ScenarioError(json_path, what + " that is nodata over the whole domain",
                      "values over the domain (nodata cells count as no disturbance)");
}

// The domain a raster bed settles: the one given, which must lie on the raster, or the
// raster's extent. Either way free of nodata.
Rectangle settle_domain(const Scenario& scene, const Field& bed) {
  const Rectangle domain = scene.domain_from_bed ? extent(bed) : scene.domain;
  const std::string path = scene.domain_from_bed ? "/bed/raster" : "/domain";
  if (!scene.domain_from_bed && !lies_on(domain, extent(bed))) {
    throw ScenarioError(path,
                        describe_box(domain) + ", reaching beyond the bed raster's extent " +
                            describe_box(extent(bed)),
                        "a domain lying on the bed raster (or no \"domain\": the raster's extent)");
  }
  const auto nodata = bed.nodata_in(domain.x_min, domain.x_max, domain.y_min, domain.y_max);
  if (nodata.count > 0) {
    throw ScenarioError(path,
                        nodata_cells(nodata.count) +
                            " of the bed raster inside the domain, the first centred at " +
                            fmt_point(nodata.x_m, nodata.y_m),
                        "a domain without bed nodata: shrink the domain to avoid them, or fill "
                        "the raster's gaps");
  }
  return domain;
}

// The bed as a source of z_b, or none when the scene names no bed (flat at z = 0).
std::shared_ptr<const swe::BedSource> analytic_bed(const BedSpec& spec) {
  if (const auto* plane = std::get_if<PlaneBedSpec>(&spec)) {
    return std::make_shared<swe::PlaneBed>(plane->elevation_m, plane->slope, plane->origin_m);
  }
  if (const auto* profile = std::get_if<ProfileBedSpec>(&spec)) {
    return std::make_shared<swe::ProfileBed>(profile->points);
  }
  return nullptr;
}

// Manning's n from a raster, sampled where each particle stands.
class RasterRoughness final : public swe::RoughnessSource {
 public:
  explicit RasterRoughness(FieldPtr field) : field_(std::move(field)) {}
  double manning_n(double x_m, double y_m) const override { return field_->sample(x_m, y_m); }

 private:
  FieldPtr field_;
};

// ---------------------------------------------------------------------------------------------
// Particles

struct Seeded {
  particles::SweParticles particles;
  std::vector<double> target_depth_m;  // the depth each particle starts with, by index
  // By index: whether the particle's depth came from the terrain (a level or a depth raster).
  std::vector<std::uint8_t> from_terrain;
  StartingVolumes volumes;
  // The finest body's lattice, continued over the domain as the bed the water sees
  // (swe/bed_lattice.hpp); absent without water bodies.
  std::optional<swe::BedLatticeGeometry> lattice;
  // Points left dry because their water was no deeper than min_depth: (x, y, surface there).
  std::vector<std::array<double, 3>> thin_film;
};

// Where (x, y) the body is this deep, or NaN (or no more than min_depth): dry.
double starting_depth(const WaterBody& body, const Field* depth_raster, const swe::BedSource* bed,
                      double x, double y, double z_b) {
  if (const auto* uniform = std::get_if<UniformDepth>(&body.depth)) return uniform->depth_m;
  if (const auto* level = std::get_if<LevelSurface>(&body.depth)) {
    return bed ? level->surface_elevation_m - z_b : std::numeric_limits<double>::quiet_NaN();
  }
  // Beyond the raster's edges it holds its edge values; water there is not the raster's.
  if (!depth_raster->covers(x, y)) return std::numeric_limits<double>::quiet_NaN();
  return depth_raster->sample(x, y);
}

std::string no_water_message(const WaterBody& body, std::size_t points, double bed_min,
                             double bed_max) {
  std::string found = "no lattice point deeper than min_depth = " + fmt(body.min_depth_m) +
                      " m among the " + std::to_string(points) + " in the shape";
  if (const auto* level = std::get_if<LevelSurface>(&body.depth)) {
    found += " (surface_elevation " + fmt(level->surface_elevation_m) + " m, bed " + fmt(bed_min) +
             " to " + fmt(bed_max) + " m there)";
    return found;
  }
  return found + " (the depth raster is dry or nodata there)";
}

// A lake filled to a level from a point (LevelSurface::from): which lattice points hold its
// water, connected to the point through points below the level (its shore's films included).
// Empty: every point of the shape may.
std::vector<char> lake_from_point(const WaterBody& body, const particles::Lattice& lattice,
                                  const std::vector<double>& depth_at, std::size_t index) {
  const auto* level = std::get_if<LevelSurface>(&body.depth);
  if (!level || !level->from) return {};
  std::vector<char> below(depth_at.size());
  for (std::size_t m = 0; m < depth_at.size(); ++m) below[m] = depth_at[m] > 0.0 ? 1 : 0;
  auto lake = particles::connected_to(lattice, below, *level->from);
  if (std::find(lake.begin(), lake.end(), 1) == lake.end()) {
    const auto [x, y] = *level->from;
    throw ScenarioError(index_path("/water", index) + "/fill/from",
                        "the lattice point nearest (" + fmt(x) + ", " + fmt(y) +
                            ") is dry: the bed there is above surface_elevation " +
                            fmt(level->surface_elevation_m) + " m",
                        "a point in the basin to fill, where the bed is below the level");
  }
  return lake;
}

Seeded seed_water(const Scenario& scene, const Terrain& terrain) {
  Seeded out;
  auto& p = out.particles;
  // Provenance is kept only when the output asks for it: otherwise it costs nothing.
  const ProvenanceOutput& provenance = scene.output.provenance;
  p.track_provenance(provenance.sources ? provenance_labels(scene).size() : 0, provenance.age);
  if (scene.output.pathlines) p.track_pathlines();
  const swe::BedSource* bed = terrain.bed.get();
  // The still water's depth is measured over the floor before a rupture: the water over the
  // floor keeps its depth as the floor moves, so its surface moves with the floor.
  const swe::BedSource* still_bed =
      terrain.fault_source ? terrain.bed_before_rupture.get() : terrain.bed.get();
  for (std::size_t i = 0; i < scene.water.size(); ++i) {
    const WaterBody& body = scene.water[i];
    const auto polygon = body.polygon.empty() ? corners(terrain.domain) : body.polygon;
    const auto lattice = particles::fill_polygon(polygon, body.spacing_m);
    if (!out.lattice || lattice.dx_m * lattice.dy_m < out.lattice->dx_m * out.lattice->dy_m) {
      out.lattice = swe::BedLatticeGeometry{lattice.corner[0], lattice.corner[1], lattice.dx_m,
                                            lattice.dy_m, lattice.cell_area_m2};
    }
    const bool uniform = std::holds_alternative<UniformDepth>(body.depth);
    out.volumes.from_terrain = out.volumes.from_terrain || !uniform;
    double bed_min = std::numeric_limits<double>::infinity(), bed_max = -bed_min;
    const std::size_t count = lattice.points.size();
    std::vector<double> bed_at(count), depth_at(count);
    for (std::size_t m = 0; m < count; ++m) {
      const auto& point = lattice.points[m];
      bed_at[m] = bed ? bed->elevation(point[0], point[1]) : 0.0;
      const double still_z = still_bed ? still_bed->elevation(point[0], point[1]) : 0.0;
      bed_min = std::min(bed_min, still_z);
      bed_max = std::max(bed_max, still_z);
      depth_at[m] = starting_depth(body, terrain.water_depth[i].get(), still_bed, point[0],
                                   point[1], still_z);
    }
    const std::vector<char> in_lake = lake_from_point(body, lattice, depth_at, i);
    const StartingSurface start(scene, terrain, i);
    const particles::Origin origin{provenance_label(scene, body.name), 0.0};
    const bool displaced = !std::holds_alternative<std::monostate>(body.displacement);
    std::size_t added = 0;
    for (std::size_t m = 0; m < count; ++m) {
      const auto& point = lattice.points[m];
      const double z_b = bed_at[m];
      double h = depth_at[m];
      // Below the level but beyond the rim of a lake filled from a point: dry ground.
      if (!in_lake.empty() && !in_lake[m]) continue;
      // Inside a building's walls: no water (buildings raised into the bed are bed).
      if (terrain.building_footprints && terrain.building_footprints->contains(point[0], point[1]))
        continue;
      // NaN fails the test too: dry.
      if (!uniform && !(h > body.min_depth_m)) {
        if (h > 0.0) out.thin_film.push_back({point[0], point[1], z_b + h});
        continue;
      }
      // A displaced surface rises (or falls) where the still body holds water: ground the
      // still level leaves dry stays dry (a fault's uplift of the land holds no water).
      if (displaced) {
        h += start.rise(point[0], point[1]);
        if (!(h > body.min_depth_m)) {
          if (h > 0.0 && !uniform) out.thin_film.push_back({point[0], point[1], z_b + h});
          continue;
        }
      }
      const auto [u, v] = start.velocity(point[0], point[1]);
      // Each particle carries the water of its lattice cell: the scene's volume exactly.
      p.add_fluid(point[0], point[1], u, v, h * lattice.cell_area_m2, h, lattice.cell_area_m2, z_b,
                  origin);
      out.target_depth_m.push_back(h);
      out.from_terrain.push_back(uniform ? 0 : 1);
      out.volumes.geometric_m3 += h * lattice.cell_area_m2;
      ++added;
    }
    if (!uniform && added == 0) {
      throw ScenarioError(index_path("/water", i),
                          no_water_message(body, lattice.points.size(), bed_min, bed_max),
                          "water deeper than min_depth somewhere in the shape (raise the "
                          "surface, lower min_depth or refine the spacing)");
    }
  }
  return out;
}

boundaries::GhostWalls make_walls(const std::vector<Wall>& walls,
                                  std::vector<boundaries::WallSegment> segments) {
  for (const auto& wall : walls) {
    const auto condition = wall.condition == WallCondition::slip
                               ? boundaries::WallCondition::slip
                               : boundaries::WallCondition::no_slip;
    for (std::size_t k = 0; k + 1 < wall.polyline.size(); ++k) {
      segments.push_back({wall.polyline[k], wall.polyline[k + 1], condition});
    }
  }
  return boundaries::GhostWalls(std::move(segments));
}

// The rasters each water body's starting surface names: its rise and its velocity's
// components, warped to the scene's CRS like the others.
void read_starting_rasters(const Scenario& scene, SceneCrs& crs, Terrain& terrain) {
  const std::size_t bodies = scene.water.size();
  terrain.displacement.resize(bodies);
  terrain.velocity_u.resize(bodies);
  terrain.velocity_v.resize(bodies);
  const auto read = [&](const RasterSpec& spec, const std::string& what, const std::string& path) {
    auto field = std::make_shared<const Field>(crs.read(spec, what, "bed.crs", path));
    check_overlaps(*field, terrain.domain, path, "a " + what);
    return field;
  };
  for (std::size_t i = 0; i < bodies; ++i) {
    const WaterBody& body = scene.water[i];
    const std::string path = index_path("/water", i);
    if (const auto* raster = std::get_if<DisplacementRaster>(&body.displacement)) {
      terrain.displacement[i] =
          read(raster->raster, "surface displacement raster", path + "/surface_displacement");
    }
    if (body.velocity_rasters) {
      terrain.velocity_u[i] =
          read(body.velocity_rasters->u, "east velocity raster", path + "/velocity/u");
      terrain.velocity_v[i] =
          read(body.velocity_rasters->v, "north velocity raster", path + "/velocity/v");
    }
  }
}

// The cells a fault source's displacement is sampled on: the finest particle spacing of the
// scene's water and inflows, but no more than kMaxDisplacementCells over the domain (a grid the
// particles cannot resolve finer than their own spacing; docs/tsunami.md, "Fault sources").
double displacement_cell(const Scenario& scene, const Rectangle& domain) {
  constexpr double kMaxDisplacementCells = 4e6;
  const double finest = finest_spacing(scene);
  const double area = (domain.x_max - domain.x_min) * (domain.y_max - domain.y_min);
  return std::max(finest, std::sqrt(area / kMaxDisplacementCells));
}

// The floor after an instantaneous rupture of the scene's fault planes, its displacement
// sampled on cells of `cell_m` (tsunami::sample_displacement). Planes placed by longitude and
// latitude are projected to the scene's CRS, their strike turned from true north to the
// map's; every plane's top edge midpoint must lie in the domain.
void rupture(const FaultSourceSpec& spec, double cell_m, Terrain& terrain) {
  std::vector<tsunami::FaultPlane> planes;
  for (std::size_t i = 0; i < spec.planes.size(); ++i) {
    tsunami::FaultPlane plane = spec.planes[i].plane;
    const std::string path = index_path("/fault_source/planes", i);
    if (const auto& lon_lat = spec.planes[i].longitude_latitude) {
      try {
        const auto projected =
            io::project_geographic((*lon_lat)[0], (*lon_lat)[1], terrain.crs_wkt);
        plane.top_centre_m = {projected.x_m, projected.y_m};
        plane.strike_deg += projected.north_bearing_deg;
      } catch (const std::runtime_error& e) {
        throw ScenarioError(path, e.what(),
                            "a position in a scene with a projected CRS (a raster bed's, or "
                            "\"x\" and \"y\" on the map)");
      }
      const auto [x, y] = plane.top_centre_m;
      const Rectangle& d = terrain.domain;
      if (x < d.x_min || x > d.x_max || y < d.y_min || y > d.y_max) {
        throw ScenarioError(path,
                            "the top edge's midpoint at " + fmt_point(x, y) +
                                " outside the domain " + describe_box(d),
                            "a fault plane's top edge midpoint lying inside the domain");
      }
    }
    planes.push_back(plane);
  }
  try {
    terrain.fault_source =
        std::make_shared<const tsunami::FaultSource>(std::move(planes), spec.poisson_ratio);
  } catch (const std::invalid_argument& e) {
    throw ScenarioError("/fault_source", e.what(), "fault planes the source accepts");
  }
  terrain.bed_before_rupture = terrain.bed;
  const Rectangle& d = terrain.domain;
  terrain.bed = std::make_shared<tsunami::RupturedBed>(
      terrain.bed, tsunami::sample_displacement(*terrain.fault_source, d.x_min, d.x_max, d.y_min,
                                                d.y_max, cell_m));
}

// The scene's building files, read in its CRS: footprints raised into the bed raster, or
// kept as walls (buildings.hpp).
void add_buildings(const Scenario& scene, Terrain& terrain) {
  if (scene.buildings.empty()) return;
  const std::vector<BuildingSet> sets = read_buildings(scene, terrain.crs_wkt);
  for (const BuildingSet& set : sets) {
    terrain.buildings.push_back(
        {set.spec->key_path, set.layer, set.footprints.size(), set.not_polygons, set.degenerate});
    if (set.spec->as == BuildingsSpec::As::bed && !terrain.bed_raster) {
      throw ScenarioError(set.spec->key_path + "/as", "\"bed\" without a bed raster",
                          "\"walls\", or a \"bed\" with a \"raster\" to raise them into");
    }
  }
  const bool raised = std::any_of(sets.begin(), sets.end(), [](const BuildingSet& set) {
    return set.spec->as == BuildingsSpec::As::bed;
  });
  if (raised) {
    terrain.bed_raster = std::make_shared<const Field>(raise_buildings(sets, *terrain.bed_raster));
    terrain.bed = std::make_shared<terrain::RasterBed>(terrain.bed_raster);
  }
  terrain.building_footprints = wall_footprints(sets);
  terrain.building_walls = building_walls(sets);
}

}  // namespace

Terrain read_terrain(const Scenario& scene) {
  Terrain terrain;
  terrain.domain = scene.domain;
  SceneCrs crs;
  if (const auto* spec = std::get_if<RasterBedSpec>(&scene.bed)) {
    auto surface = crs.read_surface(spec->raster, "bed raster", "bed.crs", "/bed/raster",
                                    static_cast<std::size_t>(spec->refinement));
    auto field = std::make_shared<const Field>(std::move(surface.field));
    terrain.domain = settle_domain(scene, *field);
    terrain.bed_raster = field;
    terrain.bed_cells = surface.cells;
    terrain.bed_refinement = surface.refinement;
    terrain.bed = std::make_shared<terrain::RasterBed>(field);
  } else {
    terrain.bed = analytic_bed(scene.bed);
  }
  if (scene.domain_from_bed) check_within_domain(scene, terrain.domain);

  if (scene.manning_n) {
    if (const auto* spec = std::get_if<RasterSpec>(&*scene.manning_n)) {
      const std::string path = "/friction/manning_n_raster";
      auto field = std::make_shared<const Field>(
          crs.read(*spec, "Manning's n raster", "friction.crs", path));
      check_covers(*field, terrain.domain, path, "a Manning's n raster");
      check_positive(*field, terrain.domain, path);
      terrain.roughness = field;
    } else if (const auto* land_use = std::get_if<LandUseSpec>(&*scene.manning_n)) {
      const std::string path = "/friction/land_use_raster";
      const Field classes = crs.read(land_use->raster, "land-use raster", "friction.crs", path,
                                     io::RasterRequest::Resampling::nearest);
      check_covers(classes, terrain.domain, path, "a land-use raster");
      terrain.roughness = std::make_shared<const Field>(
          roughness_of_land_use(classes, land_use->manning_n, terrain.domain, path));
    }
  }
  terrain.water_depth.resize(scene.water.size());
  for (std::size_t i = 0; i < scene.water.size(); ++i) {
    if (const auto* depth = std::get_if<DepthRaster>(&scene.water[i].depth)) {
      const std::string path = index_path("/water", i);
      terrain.water_depth[i] = std::make_shared<const Field>(
          crs.read(depth->raster, "water depth raster", "water[" + std::to_string(i) + "].crs",
                   path + "/depth_raster"));
    }
  }
  read_starting_rasters(scene, crs, terrain);
  read_rain_maps(scene, crs, terrain);
  terrain.crs_wkt = crs.wkt();
  add_buildings(scene, terrain);
  if (scene.output.pathlines) {
    terrain.pathline_area = pathline_area(*scene.output.pathlines, terrain.crs_wkt);
  }
  if (scene.fault_source) {
    rupture(*scene.fault_source, displacement_cell(scene, terrain.domain), terrain);
  }
  return terrain;
}

// The lattice the balanced bed term sees the bed on: the finest water body's seeding lattice,
// or without water bodies one of the finest inflow's or rain's spacing from the domain's corner
// (with neither, a hundredth of the domain's shorter side). It reaches past the domain by the
// widest support a particle can take (h = kappa sqrt(cap A_0)).
std::shared_ptr<const swe::BedLattice> make_bed_lattice(const Scenario& scene,
                                                        const Terrain& terrain,
                                                        const Seeded& water) {
  const auto& seeded = water.lattice;
  const Rectangle& d = terrain.domain;
  swe::BedLatticeGeometry geometry;
  if (seeded) {
    geometry = *seeded;
  } else {
    // Finer than the particles it serves would only cost time: each particle weighs every
    // node under its kernel, so a lattice at a hundredth of a narrow domain (0.6 m under
    // 4 m particles) made the bed term 125 s of a 143 s run (docs/verification.md).
    double spacing = std::min(d.x_max - d.x_min, d.y_max - d.y_min) / 100.0;
    if (const double finest = finest_spacing(scene); finest > 0.0) spacing = finest;
    geometry = {d.x_min, d.y_min, spacing, spacing, spacing * spacing};
  }
  double widest_cell = geometry.node_area_m2;
  for (const auto& body : scene.water)
    widest_cell = std::max(widest_cell, body.spacing_m * body.spacing_m);
  for (const auto& inflow : scene.inflows)
    widest_cell = std::max(widest_cell, inflow.spacing_m * inflow.spacing_m);
  for (const auto& rain : scene.rain)
    widest_cell = std::max(widest_cell, rain.spacing_m * rain.spacing_m);
  const double margin = 2.0 * scene.numerics.kappa *
                        std::sqrt(scene.numerics.area_ratio_cap() * widest_cell) *
                        (1.0 + swe::ConservativeScheme::kSearchMargin);
  auto lattice = std::make_shared<swe::BedLattice>(
      *terrain.bed, geometry, swe::DomainBox{d.x_min, d.x_max, d.y_min, d.y_max}, margin);
  for (const auto& [x, y, surface] : water.thin_film) lattice->raise_node_at(x, y, surface);
  return lattice;
}

BuiltScene build(const Scenario& scene) {
  Terrain terrain = read_terrain(scene);
  // The rasters are in memory by now; what grows with the scene from here on is the particles
  // and the output grid, refused here rather than by the allocator.
  check_fits_in_memory(swe_memory_need(scene, terrain), usable_memory_bytes());
  auto walls = make_walls(scene.walls, terrain.building_walls);
  // Effects in the order they act within their stage.
  std::vector<std::unique_ptr<swe::Effect>> effects;
  if (scene.splitting) {
    splitting::SplittingSettings split = *scene.splitting;
    split.radius_cap_area_ratio = scene.numerics.area_ratio_cap();
    effects.push_back(std::make_unique<splitting::ParticleSplitting>(
        split,
        std::vector<boundaries::WallSegment>(walls.segments().begin(), walls.segments().end())));
  }
  // A level bed exerts no force: its elevation is set once on the particles (and inherited
  // by daughters), and no effect runs.
  const auto* plane = std::get_if<PlaneBedSpec>(&scene.bed);
  const bool level =
      plane && plane->slope[0] == 0.0 && plane->slope[1] == 0.0 && !scene.fault_source;
  Seeded seeded = seed_water(scene, terrain);
  const bool conservative = scene.numerics.scheme == swe::SchemeKind::conservative;
  if (terrain.bed && !level && conservative && scene.numerics.bed_term == swe::BedTerm::balanced) {
    // The bed seen through each particle's kernel on the seeding lattice: water filled to a
    // level stays at rest (swe/balanced_bed_slope.hpp).
    effects.push_back(std::make_unique<swe::BalancedBedSlope>(
        terrain.bed, make_bed_lattice(scene, terrain, seeded)));
  } else if (terrain.bed && !level) {
    // The bed term pairs with the depth force: eq 6 on z_b beside the seed's eq 6 depth
    // gradient; the exact bed gradient beside a force that is the exact gradient of the summed
    // depth (the seed's summation variant and the conservative scheme).
    const swe::GradientVariant bed_gradient =
        conservative ? swe::GradientVariant::summation : scene.numerics.gradient;
    effects.push_back(std::make_unique<swe::BedSlope>(terrain.bed, bed_gradient));
  }
  // A force: it acts with the depth gradient and the bed slope, before friction (velocity stage).
  if (scene.eddy_viscosity_m2_s) {
    effects.push_back(std::make_unique<swe::EddyViscosity>(*scene.eddy_viscosity_m2_s));
  }
  if (scene.shock_viscosity) {
    effects.push_back(std::make_unique<swe::ShockViscosity>(*scene.shock_viscosity));
  }
  if (terrain.roughness) {
    effects.push_back(std::make_unique<swe::ManningFriction>(
        std::make_shared<const RasterRoughness>(terrain.roughness)));
  } else if (scene.manning_n) {
    effects.push_back(std::make_unique<swe::ManningFriction>(std::get<double>(*scene.manning_n)));
  }
  // Outflow lines read the positions before the move, which an effect removing particles
  // would shift: they come first in the topology stage. Inflows only add particles, so they
  // may follow; new rows are tested by the lines from the next step on, when they have a path.
  if (!scene.outflows.empty()) effects.push_back(make_outflow(scene.outflows));
  for (std::size_t i = 0; i < scene.inflows.size(); ++i) {
    effects.push_back(
        make_inflow(scene.inflows[i], i, terrain, provenance_label(scene, scene.inflows[i].name)));
  }
  // Sea boundaries remove particles without reading the positions before the move; they come
  // before the domain's edges, which would take the same particles without a word.
  for (std::size_t i = 0; i < scene.sea_boundaries.size(); ++i) {
    effects.push_back(make_sea_boundary(scene.sea_boundaries[i], i, terrain, scene.walls,
                                        seeded.particles,
                                        provenance_label(scene, scene.sea_boundaries[i].name)));
  }
  const auto& d = terrain.domain;
  effects.push_back(std::make_unique<boundaries::DomainOutflow>(
      boundaries::Box{d.x_min, d.x_max, d.y_min, d.y_max}));
  // Rain finds the water over its cells where the step left it, every particle that left the
  // domain gone; what it creates is summed before merging may take it.
  for (std::size_t i = 0; i < scene.rain.size(); ++i) {
    effects.push_back(make_rain(scene.rain[i], terrain.rain.at(i), terrain,
                                provenance_label(scene, scene.rain[i].name)));
  }
  // Merging removes particles too, so it comes after every effect that reads the positions
  // before the move; it merges the particles let in this step only once they are summed.
  if (scene.merging) {
    effects.push_back(std::make_unique<splitting::ParticleMerging>(
        *scene.merging,
        std::vector<boundaries::WallSegment>(walls.segments().begin(), walls.segments().end())));
  }

  swe::Simulation sim(std::move(seeded.particles), scene.numerics, std::move(walls),
                      std::move(effects));
  const bool balanced = std::any_of(scene.water.begin(), scene.water.end(), [](const auto& w) {
    return w.volumes == VolumeRule::balanced;
  });
  if (balanced && !seeded.target_depth_m.empty()) {
    const double deepest =
        *std::max_element(seeded.target_depth_m.begin(), seeded.target_depth_m.end());
    // Round-off in the depth sums is about 1e-16 of the depth; 1e-10 leaves room for the
    // iteration to stop well before that and is still far below any physical depth.
    seeded.volumes.balance_tolerance_m = std::max(1e-12, 1e-10 * deepest);
    // Convergence is linear, at a rate set by how far the lattice is from balanced; a few
    // hundred passes cover the steep shores of real terrain.
    constexpr int kMaxBalanceIterations = 400;
    const std::size_t seeded_count = seeded.target_depth_m.size();
    const auto report =
        sim.balance_volumes(std::move(seeded.target_depth_m), seeded.volumes.balance_tolerance_m,
                            kMaxBalanceIterations);
    // Short of the tolerance the lake starts with ripples, which the run reports; a depth
    // error of a per cent of the water or worse means balancing failed, and running from it
    // would only hide that.
    if (!(report.max_depth_error_m <= 0.01 * deepest) || !std::isfinite(report.volume_after_m3)) {
      const auto first = std::find_if(scene.water.begin(), scene.water.end(), [](const auto& w) {
        return w.volumes == VolumeRule::balanced;
      });
      throw ScenarioError(
          index_path("/water", static_cast<std::size_t>(first - scene.water.begin())) + "/volumes",
          "balancing that failed: a depth error of " + fmt(report.max_depth_error_m) + " m after " +
              std::to_string(report.iterations) + " passes (deepest water " + fmt(deepest) +
              " m), " + std::to_string(report.removed_particles) + " of " +
              std::to_string(seeded_count) + " particles removed as unbalanceable shore",
          "water whose particle volumes can be balanced; \"volumes\": \"geometric\" starts "
          "from depth x cell area instead");
    }
    seeded.volumes.balance = report;
  } else if (std::find(seeded.from_terrain.begin(), seeded.from_terrain.end(), 1) !=
             seeded.from_terrain.end()) {
    // Water from terrain is at rest where its summed areas are (see the method's comment).
    // Balanced volumes are left out: balancing makes each area V / target, and may remove
    // particles, which the flags would not follow.
    sim.take_summed_areas_as_created(std::move(seeded.from_terrain));
  }
  return BuiltScene{std::move(terrain), std::move(sim), seeded.volumes};
}

swe::Simulation make_simulation(const Scenario& scene) {
  return std::move(build(scene).simulation);
}

}  // namespace swemps::scenario
