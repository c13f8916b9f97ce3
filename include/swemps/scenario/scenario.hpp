#pragma once
// A validated scene: plain structs, filled from scenario.json by load() and checked there.
// Nothing below this module knows JSON exists. Files the scene names (rasters, hydrograph
// tables) are only named here; build reads them.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "swemps/hydrology/rain.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/maps/hazard.hpp"
#include "swemps/ns/settings.hpp"
#include "swemps/splitting/particle_merging.hpp"
#include "swemps/splitting/particle_splitting.hpp"
#include "swemps/swe/settings.hpp"
#include "swemps/tsunami/okada.hpp"

namespace swemps::scenario {

using Point = std::array<double, 2>;  // (x, y) in m

struct Rectangle {
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;  // m
};

// A raster the scene reads: bed elevation, Manning's n or water depth.
struct RasterSpec {
  // Absolute once loaded; or a GDAL dataset name such as NETCDF:"/abs/file.nc":elevation.
  std::filesystem::path path;
  // The projected CRS (metres) to warp the raster to, as the scene gives it ("EPSG:32616");
  // empty when the scene gives none.
  std::string crs;
};

// How deep a body of water is where it starts.
struct UniformDepth {
  double depth_m = 0.0;  // above the bed, everywhere in the shape
};
// A lake filled to a level: depth z_s - z_b(x), which needs a bed.
struct LevelSurface {
  double surface_elevation_m = 0.0;  // z_s
  // Set: the lake is only the water connected to this point (through lattice points below the
  // level, its shore's films included), so that a basin fills to its level and the lower ground
  // beyond its rim stays dry.
  std::optional<Point> from;
};
// Depth read from a raster; its nodata cells are dry.
struct DepthRaster {
  RasterSpec raster;
};
using WaterDepth = std::variant<UniformDepth, LevelSurface, DepthRaster>;

// What a body's surface starts with besides its depth (a tsunami's initial condition): a
// rise eta(x, y) added to the depth where the undisturbed body holds water.
// A solitary wave (tsunami/solitary_wave.hpp); its velocity is added to the body's.
struct SolitaryWaveStart {
  double height_m = 0.0;
  // Absent: the still depth under the crest point (the body's depth, or its level less the bed).
  std::optional<double> still_depth_m;
  Point crest_m{0.0, 0.0};
  std::array<double, 2> direction{1.0, 0.0};  // non-zero
};
// A raster of the rise (m); nodata cells and points off the raster do not rise.
struct DisplacementRaster {
  RasterSpec raster;
};
using SurfaceDisplacement = std::variant<std::monostate, SolitaryWaveStart, DisplacementRaster>;
// The starting velocity read from two rasters (m/s), east and north; nodata cells and points
// off a raster are still in that component.
struct VelocityRasters {
  RasterSpec u, v;
};

// How the particles' volumes are set.
enum class VolumeRule {
  geometric,  // V = depth x lattice cell area: the shape's volume exactly
  balanced,   // rescaled so that eq 7 gives each particle its starting depth: water at rest
};

// A body of water, filled with particles on a square lattice of the given spacing.
struct WaterBody {
  // Its water's provenance label (docs/provenance.md): bodies with one name share one label.
  std::string name = kDefaultName;
  static constexpr const char* kDefaultName = "water";
  // Counter-clockwise or clockwise, not closed, >= 3 vertices (a rectangle is stored as its
  // 4 corners). Empty only for a depth raster without a shape: then the whole domain.
  std::vector<Point> polygon;
  WaterDepth depth;
  // Level surface and depth raster: lattice points this shallow or dry get no particle.
  double min_depth_m = 0.01;
  std::array<double, 2> velocity_m_s{0.0, 0.0};
  // Set: the velocity comes from these rasters instead of velocity_m_s.
  std::optional<VelocityRasters> velocity_rasters;
  SurfaceDisplacement displacement;  // uniform depths and levels only
  double spacing_m = 0.0;
  VolumeRule volumes = VolumeRule::geometric;
};

enum class WallCondition { slip, no_slip };

// A wall is a polyline of straight segments; particles are kept on the side they start on.
struct Wall {
  std::vector<Point> polyline;  // >= 2 vertices
  WallCondition condition = WallCondition::slip;
};

// Buildings (or any obstacle) drawn as polygons in a vector file (docs/buildings.md).
struct BuildingsSpec {
  std::string key_path;        // where the file gives them ("/buildings" or "/buildings/1")
  std::filesystem::path file;  // absolute
  std::string layer;           // empty: the file's first layer
  // walls: each ring a closed wall the water flows around; bed: the bed under each footprint
  // raised by height_m (the water may overtop it).
  enum class As { walls, bed };
  As as = As::walls;
  WallCondition condition = WallCondition::slip;  // walls
  double height_m = kDefaultHeightM;              // bed
  std::string crs;                                // the file's CRS when it declares none
  bool reproject = false;                         // transform a file in another CRS to the scene's
  // Higher than any flood a scene here has met: the water goes round, as it would a wall.
  static constexpr double kDefaultHeightM = 10.0;
};

// Analytic beds. No bed at all (the default) is a flat bed at z = 0 and costs nothing.
struct PlaneBedSpec {
  double elevation_m = 0.0;               // z_b at the origin
  std::array<double, 2> slope{0.0, 0.0};  // dz_b/dx, dz_b/dy (m/m)
  Point origin_m{0.0, 0.0};
};
struct ProfileBedSpec {
  std::vector<Point> points;  // (x, z_b) in m, x strictly increasing; level beyond the ends
};
// A terrain model. Its CRS (raster.crs, or the file's own) is the scene's: every other raster
// is warped to it, and the output is georeferenced in it.
struct RasterBedSpec {
  RasterSpec raster;
  // A warped raster's cells are split refinement x refinement before the bed is interpolated
  // (io::read_raster_surface): the bed follows the source DEM, not a coarse resampling of it.
  int refinement = kDefaultBedRefinement;
  static constexpr int kDefaultBedRefinement = 4;
};
using BedSpec = std::variant<std::monostate, PlaneBedSpec, ProfileBedSpec, RasterBedSpec>;

// A land-use map: a raster of whole-number classes and the Manning's n of each class
// (s m^-1/3). Build turns it into a roughness map; every class met over the domain must have an n.
struct LandUseSpec {
  RasterSpec raster;
  std::map<long long, double> manning_n;  // class -> n, > 0
};

// Manning's n (s m^-1/3): one value for the whole bed, a roughness map, or a land-use map and
// its table.
using ManningSpec = std::variant<double, RasterSpec, LandUseSpec>;

// A line water enters through, at the rate of a discharge hydrograph.
struct Inflow {
  std::string name;
  std::array<Point, 2> line;
  // (time s, discharge m^3/s) points, or a CSV file of them (absolute path).
  std::variant<std::vector<std::array<double, 2>>, std::filesystem::path> hydrograph;
  double spacing_m = 0.0;
  std::optional<double> depth_m;  // absent: the critical depth of the discharge
  // The way the water enters, normal to the line; absent: towards the domain's centre.
  std::optional<std::array<double, 2>> direction;
};

// A number, or a raster of numbers, for a quantity that may vary over the domain.
using ValueOrRaster = std::variant<double, RasterSpec>;

// Green-Ampt infiltration's soil (hydrology/rain_losses.hpp), each value in the scene's units.
struct GreenAmptSpec {
  ValueOrRaster conductivity_mm_h = 0.0;  // K, the saturated hydraulic conductivity
  ValueOrRaster suction_mm = 0.0;         // psi, the suction head at the wetting front
  ValueOrRaster moisture_deficit = 0.0;   // dtheta, 0..1
};

// Rain over the domain or a polygon of it (hydrology/rain.hpp, docs/rain.md).
struct RainSpec {
  std::string name;
  std::string key_path;  // where the file gives it ("/rain" or "/rain/2"), for messages
  // A map of the rate (mm/h), constant in time; and a netCDF series of such maps over
  // (time, y, x), each holding until the next (hydrology::MappedRainRate).
  struct RateRaster {
    RasterSpec raster;
  };
  struct RateNetcdf {
    RasterSpec raster;
  };
  // (time s, rate mm/h) points, or a CSV file of them (absolute path), one rate for the whole
  // rain (one point is a constant rate); or maps of the rate.
  std::variant<std::vector<std::array<double, 2>>, std::filesystem::path, RateRaster, RateNetcdf>
      rate_mm_h;
  std::vector<Point> polygon;  // empty: the whole domain
  double spacing_m = 0.0;      // of the rain's cells and the particles it creates
  double creation_depth_m = hydrology::RainSettings::kDefaultCreationDepthM;
  ValueOrRaster initial_loss_mm = 0.0;
  ValueOrRaster continuing_loss_mm_h = 0.0;  // unused with Green-Ampt
  std::optional<GreenAmptSpec> green_ampt;   // instead of the continuing loss
};

// A polyline water leaves the domain through.
struct Outflow {
  std::vector<Point> line;  // >= 2 points
};

// A straight line where the sea goes on beyond the domain (boundaries/sea_boundary.hpp):
// waves leave through it, or its level follows a series and then lets waves leave.
struct SeaBoundarySpec {
  std::string name;
  std::array<Point, 2> line;
  // Open: the level of the sea at rest beyond the line; absent: the water's starting level
  // beside the line (build). Unused by a level boundary, open about its series' last level
  // once the series ends.
  std::optional<double> still_level_m;
  // A level boundary: (time s, level m) points, or a CSV file of them (absolute path).
  std::optional<std::variant<std::vector<std::array<double, 2>>, std::filesystem::path>> level;
  double spacing_m = 0.0;  // of the water it lets in
};

struct GridSpec {
  // Absent only with a raster bed: then the bed raster's own cells.
  std::optional<double> spacing_m;
  // Absent: the domain. Cell centres at bounds.x_min + (i + 0.5) spacing_m, ...
  std::optional<Rectangle> bounds;
};

// A point where depth and velocity are recorded over time.
struct Gauge {
  std::string name;
  Point position_m;
};

// The tsunami products of a run (docs/outputs.md, "Tsunami maps"): the maps of the rise above
// the sea's still level and of the wave's arrival, and the inundation line as a vector file.
enum class VectorFormat { none, gpkg, geojson };
struct TsunamiOutput {
  maps::TsunamiLevels levels;  // the still level given, or the level the scene's sea is filled to
  VectorFormat inundation_line = VectorFormat::gpkg;
};

// What a run writes of where its water came from and how long it has been in the domain
// (docs/provenance.md). Nothing of it is kept, or costs anything, unless asked for.
struct ProvenanceOutput {
  // Per provenance label (provenance_labels()): its water's depth and share of the depth at
  // output times and their whole-run maxima, its volume balance, and its share at each gauge.
  bool sources = false;
  // The volume-weighted mean age of the water (time since it entered the domain) at output
  // times, and its whole-run maximum.
  bool age = false;
  bool any() const { return sources || age; }
};

// A file of polygons a scene names (GeoJSON, Shapefile, GeoPackage), read as the buildings'
// are (io::read_polygons): in the scene's CRS, or transformed with `reproject`.
struct PolygonFileSpec {
  std::string key_path;        // where the scene names it, for messages
  std::filesystem::path file;  // absolute
  std::string layer;           // empty: the file's first layer
  std::string crs;             // the file's CRS when it declares none; "scene": as they are
  bool reproject = false;
};

// The tracks of chosen particles, written as lines in a vector file with time as each
// vertex's M (docs/provenance.md, "Pathlines"). The particles are chosen once, at start_s,
// among those that pass every filter given, at most `count` of them spread evenly over the
// rest (in the particles' order, which follows their cells).
struct PathlineOutput {
  // Absolute, .gpkg or .geojson; empty: "<output stem>_pathlines.gpkg" beside wherever the
  // run writes its netCDF file (file()).
  std::filesystem::path path;
  VectorFormat format = VectorFormat::gpkg;
  std::filesystem::path file(const std::filesystem::path& output) const {
    if (!path.empty()) return path;
    std::filesystem::path beside = output;
    beside.replace_filename(output.stem().string() + "_pathlines.gpkg");
    return beside;
  }
  std::size_t count = 100;
  // A provenance label's name: only particles at least half of whose water is that source's.
  std::optional<std::string> source;
  // Only particles inside: a polygon given by its vertices, or the polygons of a file.
  std::vector<Point> polygon;
  std::optional<PolygonFileSpec> polygon_file;
  double start_s = 0.0;
  double interval_s = 0.0;  // between vertices: the series interval unless given
};

struct Output {
  std::filesystem::path path;   // absolute once loaded
  std::vector<double> times_s;  // sorted, unique, in (0, end_time]; t = 0 is always written too
  GridSpec grid;
  bool write_particles = true;
  std::vector<Gauge> gauges;
  double series_interval_s = 0.0;  // gauges and volume balance
  double wet_depth_m = 0.01;       // the depth a cell must exceed to count as wet
  // Further depths, each above wet_depth_m, at which the flood statistics time the arrival
  // and the duration of the water (the wet depth is always the first).
  std::vector<double> depth_thresholds_m;
  maps::LandUse land_use = maps::LandUse::urban;  // the hazard rating's debris factor
  // The real date and time of t = 0 as given (ISO 8601), and as the time axes' CF units
  // ("seconds since 2024-06-01 12:00:00 +02:00"); both absent: a nominal epoch.
  std::optional<std::string> start_time;
  std::optional<std::string> start_time_units;
  // Whole-run maps written as GeoTIFF beside the netCDF file when the run completes
  // (maps::summary_map_names() names them); empty: none. Cloud-optimised unless raster_cog is
  // false.
  std::vector<std::string> rasters;
  bool raster_cog = true;
  std::optional<TsunamiOutput> tsunami;  // absent: none of the tsunami products
  ProvenanceOutput provenance;
  std::optional<PathlineOutput> pathlines;  // absent: none
};

// An earthquake's rectangular fault planes (tsunami/okada.hpp): the floor's vertical
// displacement is added to the bed at t = 0 (an instantaneous rupture), and the water over it
// keeps its depth, so that its surface rises and falls with the floor.
struct FaultPlaneSpec {
  // Strike clockwise from the map's +y; top_centre_m set by build when the position is given
  // as longitude and latitude, and the strike then turned from true north to the map's.
  tsunami::FaultPlane plane;
  std::optional<Point> longitude_latitude;  // degrees east, north
};
struct FaultSourceSpec {
  std::vector<FaultPlaneSpec> planes;  // >= 1
  double poisson_ratio = 0.25;
};

// Which equations run the scene.
enum class Model {
  swe,  // depth-integrated shallow water over the plan (x, y): particles, walls, effects
  ns,   // incompressible Navier-Stokes in a tank (ns::Simulation): water boxes, solid walls
};

// The scene's "ns" block: how the Navier-Stokes mode runs it.
struct NsSpec {
  // Maps 1:1 onto the solver's settings; gravity_m_s2 is the scene's gravity, spacing_m is
  // l_0, and the defaults are ns::Settings' own.
  ns::Settings settings;
  // Height of the tank's side walls above the floor, a whole number of spacings. Absent only
  // when the file gives none and the scene has no water of uniform depth to take the default
  // from (twice the deepest, rounded up to whole spacings); model ns refuses such water.
  std::optional<double> tank_height_m;
};

struct Scenario {
  std::string name;
  std::string description;
  double end_time_s = 0.0;
  swe::Settings numerics;
  std::optional<double> eddy_viscosity_m2_s;  // numerics.eddy_viscosity; absent: none
  std::optional<double> shock_viscosity;      // numerics.shock_viscosity (alpha); absent: none
  // Particles leaving it are removed and their volume booked. Left out of the file with a
  // raster bed (domain_from_bed): then all zero here, and build takes the raster's extent.
  Rectangle domain;
  bool domain_from_bed = false;
  std::vector<WaterBody> water;  // may be empty when there are inflows
  std::vector<Wall> walls;
  std::vector<BuildingsSpec> buildings;
  BedSpec bed;
  std::optional<ManningSpec> manning_n;                   // absent: no friction
  std::optional<splitting::SplittingSettings> splitting;  // absent: no splitting
  std::optional<splitting::MergingSettings> merging;      // absent: no merging
  std::vector<Inflow> inflows;
  std::vector<RainSpec> rain;
  std::vector<Outflow> outflows;
  std::optional<FaultSourceSpec> fault_source;  // absent: none
  std::vector<SeaBoundarySpec> sea_boundaries;
  Output output;
  Model model = Model::swe;
  // Model ns: 2 = a vertical x-z section along x (the scene's y is ignored), 3 = x, y, z.
  int dimension = 3;
  std::optional<NsSpec> ns;  // required with model ns; optional otherwise (compare needs it)
  // The scene file's JSON with every default the reading took filled in, as text: what the
  // run's files record of the scene.
  std::string as_read_json;
};

// A problem in a scenario file: where (JSON path such as /water/0/depth), what was found,
// what was expected. what() gives all three in one line, opening with the kind of document
// ("scenario error at ..."; "study error at ..." for a study file).
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(std::string json_path, std::string found, std::string expected,
                std::string document = "scenario");
  const std::string& json_path() const { return json_path_; }
  const std::string& found() const { return found_; }
  const std::string& expected() const { return expected_; }
  const std::string& document() const { return document_; }

 private:
  std::string json_path_, found_, expected_, document_;
};

// `text` fit to be one line of a message on a terminal: control characters (a line break in a
// key or a file name) are written as escapes such as \n or \x1b, and bytes that are not UTF-8
// as \xff, so that a message stays one line and cannot drive the terminal.
std::string printable_line(std::string_view text);

// The provenance labels of the scene's water (docs/provenance.md): one per name of a source, in
// the order the scene gives them: water bodies, inflows, sea boundaries, rain. Sources that
// share a name share a label (two bodies named "lake"; bodies without a name are "water").
std::vector<std::string> provenance_labels(const Scenario& scene);
// The index of `name` in provenance_labels(scene); std::out_of_range when no source has it.
std::uint32_t provenance_label(const Scenario& scene, const std::string& name);

// Reads and validates a scenario file. Relative paths inside it are taken relative to the
// file's folder. Throws ScenarioError (file unreadable, syntax, unknown key, bad value).
Scenario load(const std::filesystem::path& file);

// The same from text; `base_dir` resolves relative paths, `default_name` names an unnamed scene.
Scenario parse(const std::string& text, const std::filesystem::path& base_dir,
               const std::string& default_name = "scenario");

// The checks that need the domain: water, inflow lines and gauges lie in it, and a grid over
// it is not absurdly fine. parse() makes them when the file gives the domain; build makes them
// once the bed raster has given it. Throws ScenarioError.
void check_within_domain(const Scenario& scene, const Rectangle& domain);

// What model ns needs of a scene, beyond what parse() checks for every scene: an "ns" block;
// water that is axis-aligned rectangles of uniform depth at rest; no bed or a level one; no
// friction, splitting, inflow or outflow; a domain whose sides (x, and y in 3D) and a tank
// height that are whole numbers of spacings, the tank at least as high as the water.
// parse() calls it for scenes with model ns; the compare command calls it for the scene it
// runs as model ns. Throws ScenarioError naming the key that is in the way.
void check_ns_scene(const Scenario& scene);

}  // namespace swemps::scenario
