// The collapse of a square water column (Martin & Moyce 1952, n^2 = 1) run with the
// Navier-Stokes MPS mode (method.md section 3), for comparing weight functions (method.md
// section 2), resolutions, and 2D against 3D. docs/ns-dam-break.md holds the tables and plots
// made from its output and explains how to read them.
//
// A column a wide and a high stands against the left wall of a tank 5a long and 2a high; in
// 3D the tank is a wide and the column fills that width, so the flow is a channel flow between
// side walls and compares with the 2D section. After every step the program records, against
// the dimensionless time T = t sqrt(2g/a), the surge front Z = z/a, two pressure probes in
// units of rho g a, the water depth over the floor probe and the solver's effort. Then the
// front is compared with the experiment and the pressure noise measured.
//
//   swemps-ns-dam-break [--dim 2|3] [--resolution N] [--kernel NAME] [--support S] ...
//
// prints one summary line (key=value) and writes samples every dT to a CSV file (every step
// to a second one if asked); --help lists the options. Run it from the source tree (or give --data)
// so that it finds the measurements.

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/ns/measures.hpp"
#include "swemps/ns/settings.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"

namespace {

namespace ns = swemps::ns;
namespace kernels = swemps::kernels;

// The experiment's column: 2.25 in.
constexpr double column_m = 0.05715;
constexpr double tank_length_columns = 5.0;
constexpr double tank_height_columns = 2.0;
// The pressure noise is measured from T = 0.5, once the column has fallen and the surge
// runs along the floor, to T = 3.0, the last time whose averaging window ends before T = 3.2.
constexpr double noise_from = 0.5, noise_to = 3.0;
// Averaging window of the noise measure: some 45 steps at a/l0 = 40, long against the
// step-to-step oscillation and short against the flow's own changes (the depth over the
// floor probe falls by about a tenth of a in it).
constexpr double noise_window = 0.2;
// The first measured points are affected by the release of the column in the experiment,
// so the error is also given from this T on.
constexpr double late_from = 1.0;
// The probes' mean pressure is also taken while the column still stands full height over the
// floor probe, to compare with the pressure just after release (docs/ns-dam-break.md).
constexpr double early_to = 0.2;

struct Options {
  int dim = 2;
  int resolution = 0;  // particles across a; 0: 40 in 2D, 20 in 3D
  ns::Settings settings;
  // Unless given, the velocity kernel is the pressure kernel.
  std::optional<kernels::KernelType> velocity_type;
  std::optional<double> velocity_support, velocity_kappa;
  int threads = 0;  // 0: OpenMP's default
  double end_T = 3.2;
  double interval_T = 0.02;
  bool land_on_samples = false;
  std::string output = "ns-dam-break.csv";
  std::string steps_output;  // empty: not written
  std::string data = "data/martin_moyce_1952_square_column.csv";
  std::string command_line;
};

const char* usage =
    "usage: swemps-ns-dam-break [options]\n"
    "  --dim 2|3                      dimension (2)\n"
    "  --resolution N                 particles across the column width a (40 in 2D, 20 in 3D)\n"
    "  --kernel NAME                  pressure kernel: standard, sheu-quartic, logarithmic,\n"
    "                                 hyperbolic, hyperbolic-sph, spiky (standard)\n"
    "  --support S                    its cut-off in spacings (2.1)\n"
    "  --kappa K                      its kappa, hyperbolic kernels (2)\n"
    "  --velocity-kernel NAME, --velocity-support S, --velocity-kappa K\n"
    "                                 the viscosity's kernel (default: the pressure kernel)\n"
    "  --source number-density|mixed  Poisson source (number-density)\n"
    "  --gamma G                      mixed source's relaxation (0.05)\n"
    "  --beta B                       free surface below B n0 (0.97)\n"
    "  --repulsion R                  corrected-repulsive: pairs closer than R l0 repel (0.9)\n"
    "  --asymmetry A                  surface only where the mean offset > A l0 (0: off)\n"
    "  --gradient minimum-pressure|corrected|corrected-repulsive (minimum-pressure)\n"
    "  --gradient-weights mps|kernel-slope  corrected gradients' pair weights (mps)\n"
    "  --boundary poisson|extrapolated          wall pressures (poisson)\n"
    "  --scheme standard|well-balanced|least-squares  every choice of that scheme; options\n"
    "                                 after it override them (standard)\n"
    "  --operators mps|least-squares  Laplacian and gradient discretisation (mps)\n"
    "  --preconditioner incomplete-cholesky|diagonal|multigrid (incomplete-cholesky)\n"
    "  --setup-solves N               solves one multigrid setup serves (5)\n"
    "  --tolerance TOL                CG relative residual (1e-6)\n"
    "  --max-iterations N             CG iteration cap (1000)\n"
    "  --courant C                    time-step Courant number (0.2)\n"
    "  --collision on|off             particle collision model (on)\n"
    "  --threads N                    OpenMP threads (OpenMP's default)\n"
    "  --end T                        last dimensionless time (3.2)\n"
    "  --interval DT                  sampling interval in T (0.02)\n"
    "  --land-on-samples on|off       step with advance_to onto every sample time instead\n"
    "                                 of always taking the stable step (off)\n"
    "  --output PATH                  samples CSV (ns-dam-break.csv)\n"
    "  --steps-output PATH            every step's probes CSV (not written)\n"
    "  --data PATH                    Martin & Moyce's front positions\n"
    "                                 (data/martin_moyce_1952_square_column.csv)\n";

double to_number(const std::string& key, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(key + " needs a number, not \"" + text + "\"");
  }
  return value;
}

int to_integer(const std::string& key, const std::string& text) {
  const double value = to_number(key, text);
  if (value != std::floor(value)) throw std::invalid_argument(key + " needs a whole number");
  return static_cast<int>(value);
}

kernels::KernelType to_kernel(const std::string& text) {
  if (const auto type = kernels::kernel_type_from_name(text)) return *type;
  throw std::invalid_argument("unknown kernel \"" + text + "\"");
}

Options parse(int argc, char** argv) {
  Options o;
  o.command_line = "swemps-ns-dam-break";
  for (int k = 1; k < argc; ++k) o.command_line += std::string(" ") + argv[k];
  auto& s = o.settings;
  // The scheme's defaults depend on the dimension, so --dim is read first wherever it stands.
  for (int k = 1; k + 1 < argc; k += 2) {
    if (std::string(argv[k]) == "--dim") o.dim = to_integer("--dim", argv[k + 1]);
  }
  for (int k = 1; k < argc; k += 2) {
    const std::string key = argv[k];
    if (key == "--help") throw std::invalid_argument("");
    if (k + 1 >= argc) throw std::invalid_argument(key + " needs a value");
    const std::string value = argv[k + 1];
    if (key == "--dim") {
      o.dim = to_integer(key, value);
      if (o.dim != 2 && o.dim != 3) throw std::invalid_argument("--dim is 2 or 3");
    } else if (key == "--resolution") {
      o.resolution = to_integer(key, value);
      if (o.resolution < 2) throw std::invalid_argument("--resolution must be at least 2");
    } else if (key == "--kernel") {
      s.pressure_kernel.spec.type = to_kernel(value);
    } else if (key == "--support") {
      s.pressure_kernel.support_spacings = to_number(key, value);
    } else if (key == "--kappa") {
      s.pressure_kernel.spec.kappa = to_number(key, value);
    } else if (key == "--velocity-kernel") {
      o.velocity_type = to_kernel(value);
    } else if (key == "--velocity-support") {
      o.velocity_support = to_number(key, value);
    } else if (key == "--velocity-kappa") {
      o.velocity_kappa = to_number(key, value);
    } else if (key == "--source") {
      if (value == "number-density") {
        s.source = ns::SourceTerm::number_density;
      } else if (value == "mixed") {
        s.source = ns::SourceTerm::mixed;
      } else {
        throw std::invalid_argument("--source is number-density or mixed");
      }
    } else if (key == "--gamma") {
      s.source_gamma = to_number(key, value);
    } else if (key == "--beta") {
      s.free_surface_beta = to_number(key, value);
    } else if (key == "--repulsion") {
      s.repulsion_distance_spacings = to_number(key, value);
    } else if (key == "--asymmetry") {
      s.free_surface_asymmetry = to_number(key, value);
    } else if (key == "--gradient") {
      if (value == "minimum-pressure") {
        s.gradient = ns::PressureGradient::minimum_pressure;
      } else if (value == "corrected") {
        s.gradient = ns::PressureGradient::corrected;
      } else if (value == "corrected-repulsive") {
        s.gradient = ns::PressureGradient::corrected_repulsive;
      } else {
        throw std::invalid_argument(
            "--gradient is minimum-pressure, corrected or corrected-repulsive");
      }
    } else if (key == "--gradient-weights") {
      const auto weights = ns::gradient_weights_from_name(value);
      if (!weights) throw std::invalid_argument("--gradient-weights is mps or kernel-slope");
      s.gradient_weights = *weights;
    } else if (key == "--scheme") {
      // Every numerical choice of the scheme; options after it override them one by one.
      if (value != "standard" && value != "well-balanced" && value != "least-squares") {
        throw std::invalid_argument("--scheme is standard, well-balanced or least-squares");
      }
      s = ns::scheme_settings(value == "standard"        ? ns::Scheme::standard
                              : value == "least-squares" ? ns::Scheme::least_squares
                                                         : ns::Scheme::well_balanced,
                              o.dim);
    } else if (key == "--operators") {
      if (value == "mps") {
        s.operators = ns::Operators::mps;
      } else if (value == "least-squares") {
        s.operators = ns::Operators::least_squares;
      } else {
        throw std::invalid_argument("--operators is mps or least-squares");
      }
    } else if (key == "--boundary") {
      if (value == "poisson") {
        s.boundary = ns::BoundaryPressure::poisson;
      } else if (value == "extrapolated") {
        s.boundary = ns::BoundaryPressure::extrapolated;
      } else {
        throw std::invalid_argument("--boundary is poisson or extrapolated");
      }
    } else if (key == "--preconditioner") {
      const auto p = ns::preconditioner_from_name(value);
      if (!p) {
        throw std::invalid_argument(
            "--preconditioner is incomplete-cholesky, diagonal or multigrid");
      }
      s.solver.preconditioner = *p;
    } else if (key == "--setup-solves") {
      s.solver.multigrid_setup_solves = to_integer(key, value);
    } else if (key == "--tolerance") {
      s.solver.relative_tolerance = to_number(key, value);
    } else if (key == "--max-iterations") {
      s.solver.max_iterations = to_integer(key, value);
    } else if (key == "--courant") {
      s.courant = to_number(key, value);
    } else if (key == "--collision") {
      if (value == "on") {
        s.collision = ns::Collision{};
      } else if (value == "off") {
        s.collision.reset();
      } else {
        throw std::invalid_argument("--collision is on or off");
      }
    } else if (key == "--threads") {
      o.threads = to_integer(key, value);
      if (o.threads < 1) throw std::invalid_argument("--threads must be at least 1");
    } else if (key == "--end") {
      o.end_T = to_number(key, value);
    } else if (key == "--interval") {
      o.interval_T = to_number(key, value);
    } else if (key == "--land-on-samples") {
      if (value != "on" && value != "off") {
        throw std::invalid_argument("--land-on-samples is on or off");
      }
      o.land_on_samples = value == "on";
    } else if (key == "--output") {
      o.output = value;
    } else if (key == "--steps-output") {
      o.steps_output = value;
    } else if (key == "--data") {
      o.data = value;
    } else {
      throw std::invalid_argument("unknown option " + key);
    }
  }
  if (!(o.interval_T > 0.0) || !(o.end_T >= o.interval_T)) {
    throw std::invalid_argument("--interval must be > 0 and --end at least one interval");
  }
  if (o.resolution == 0) o.resolution = o.dim == 2 ? 40 : 20;
  s.velocity_kernel = s.pressure_kernel;
  if (o.velocity_type) s.velocity_kernel.spec.type = *o.velocity_type;
  if (o.velocity_support) s.velocity_kernel.support_spacings = *o.velocity_support;
  if (o.velocity_kappa) s.velocity_kernel.spec.kappa = *o.velocity_kappa;
  s.spacing_m = column_m / o.resolution;
  return o;
}

// The state after one step (or at the start), in the study's units.
struct Record {
  double T = 0.0;                      // t sqrt(2g/a)
  double Z = 0.0;                      // front / a
  double p_floor = 0.0, p_wall = 0.0;  // probe pressures / (rho g a)
  double h_floor = 0.0;                // depth over the floor probe / a
  double dt_s = 0.0;
  int iterations = 0;  // Poisson iterations of the step
  double residual = 0.0;
  std::size_t fluid = 0;
};

struct ExperimentPoint {
  double T = 0.0, Z = 0.0;
};

std::vector<ExperimentPoint> read_experiment(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path + " (run from the source tree?)");
  std::vector<ExperimentPoint> points;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'T') continue;
    ExperimentPoint p;
    if (std::sscanf(line.c_str(), "%lf,%lf", &p.T, &p.Z) == 2) points.push_back(p);
  }
  if (points.empty()) throw std::runtime_error(path + " holds no T,Z rows");
  return points;
}

// Centred moving average of one probe over noise_window, step by step; NaN where the window
// reaches past the run or holds the unsolved start.
std::vector<double> centred_average(const std::vector<Record>& records, double Record::*value) {
  const double half = 0.5 * noise_window;
  std::vector<double> average(records.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < records.size(); ++k) {
    const double T = records[k].T;
    if (T - half < records.front().T || T + half > records.back().T) continue;
    double sum = 0.0;
    int count = 0;
    for (const auto& other : records) {
      if (std::abs(other.T - T) <= half) {
        sum += other.*value;
        ++count;
      }
    }
    average[k] = sum / count;  // NaN if the start is in the window
  }
  return average;
}

// RMS of the probe's departure from its moving average over [noise_from, noise_to].
double rms_noise(const std::vector<Record>& records, double Record::*value) {
  const auto average = centred_average(records, value);
  double sum = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const double T = records[k].T;
    if (T < noise_from || T > noise_to || !std::isfinite(average[k])) continue;
    const double deviation = records[k].*value - average[k];
    sum += deviation * deviation;
    ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : std::numeric_limits<double>::quiet_NaN();
}

// The front at T, linear between the steps around it; NaN past the end of the run.
double front_at(const std::vector<Record>& records, double T) {
  const auto after = std::lower_bound(records.begin(), records.end(), T,
                                      [](const Record& r, double t) { return r.T < t; });
  if (after == records.end()) return std::numeric_limits<double>::quiet_NaN();
  if (after == records.begin()) return after->Z;
  const auto& lo = *(after - 1);
  return lo.Z + (after->Z - lo.Z) * (T - lo.T) / (after->T - lo.T);
}

struct FrontError {
  int points = 0;  // measured points the run reached
  double mean = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
};

// |Z_run(T_k) - Z_k| over the measured points from T = `from` on.
FrontError front_error(const std::vector<Record>& records,
                       const std::vector<ExperimentPoint>& experiment, double from) {
  FrontError e;
  double sum = 0.0, worst = 0.0;
  for (const auto& point : experiment) {
    const double Z = front_at(records, point.T);
    if (point.T < from || !std::isfinite(Z)) continue;
    sum += std::abs(Z - point.Z);
    worst = std::max(worst, std::abs(Z - point.Z));
    ++e.points;
  }
  if (e.points > 0) {
    e.mean = sum / e.points;
    e.max = worst;
  }
  return e;
}

// Mean of one probe over [from, to].
double mean_pressure(const std::vector<Record>& records, double Record::*value, double from,
                     double to) {
  double sum = 0.0;
  int count = 0;
  for (const auto& r : records) {
    if (r.T < from || r.T > to || !std::isfinite(r.*value)) continue;
    sum += r.*value;
    ++count;
  }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

// Mean of the floor probe over [from, to] divided by the mean hydrostatic pressure of the
// depth above it (the probe sits half a spacing below the floor).
double over_hydrostatic(const std::vector<Record>& records, double from, double to,
                        double half_spacing_columns) {
  double pressure = 0.0, hydrostatic = 0.0;
  for (const auto& r : records) {
    if (r.T < from || r.T > to || !std::isfinite(r.p_floor)) continue;
    pressure += r.p_floor;
    hydrostatic += r.h_floor + half_spacing_columns;
  }
  return hydrostatic > 0.0 ? pressure / hydrostatic : std::numeric_limits<double>::quiet_NaN();
}

struct Run {
  std::size_t fluid = 0, wall = 0, dummy = 0;
  int solid_layers = 0;
  ns::RunTotals totals;
  double wall_time_s = 0.0;
  // Processor time of the whole process: with one thread it is the run's cost even on a
  // machine that other work slows down, where wall time is not.
  double cpu_time_s = 0.0;
  std::vector<Record> records;  // the start, then every step
  std::string failure;          // empty when the run reached end_T
};

template <int Dim>
Run run(const Options& o) {
  const ns::Settings& s = o.settings;
  const double a = column_m;
  const double l0 = s.spacing_m;
  const double time_scale_s = std::sqrt(a / (2.0 * s.gravity_m_s2));  // t = T time_scale_s
  const double pressure_scale_pa = s.density_kg_m3 * s.gravity_m_s2 * a;

  ns::TankSpec<Dim> tank;
  ns::Box<Dim> water;
  tank.interior.upper[0] = tank_length_columns * a;
  water.upper[0] = a;
  if constexpr (Dim == 3) {
    tank.interior.upper[1] = a;
    water.upper[1] = a;
  }
  tank.interior.upper[Dim - 1] = tank_height_columns * a;
  water.upper[Dim - 1] = a;
  tank.water = {water};
  tank.spacing_m = l0;
  // A wall particle's support must be full of solid; 1e-9 keeps a support of exactly 2.0
  // spacings at two layers.
  const double support =
      std::max(s.pressure_kernel.support_spacings, s.velocity_kernel.support_spacings);
  tank.solid_layers = static_cast<int>(std::ceil(support - 1e-9));

  Run result;
  result.solid_layers = tank.solid_layers;
  ns::Particles<Dim> particles = ns::fill_tank<Dim>(tank);
  result.fluid = particles.fluid;
  result.wall = particles.wall;
  result.dummy = particles.dummy;
  std::array<double, Dim> lower{}, upper{};
  for (int d = 0; d < Dim; ++d) {
    lower[d] = tank.interior.lower[d] - tank.solid_layers * l0;
    upper[d] = tank.interior.upper[d] + tank.solid_layers * l0;
  }

  // Kakuda's probes: one in the floor's wall-particle row at x = a/2, one in the left wall's
  // at z = a/5; in 3D on the channel's centre line.
  std::array<double, Dim> floor_probe{}, wall_probe{};
  floor_probe[0] = 0.5 * a;
  floor_probe[Dim - 1] = -0.5 * l0;
  wall_probe[0] = -0.5 * l0;
  wall_probe[Dim - 1] = 0.2 * a;
  if constexpr (Dim == 3) floor_probe[1] = wall_probe[1] = 0.5 * a;
  // The depth over the floor probe, across two particle columns (the whole width in 3D).
  ns::PlanGrid over_probe;
  over_probe.x0 = 0.5 * a;
  over_probe.dx = 2.0 * l0;
  over_probe.y0 = 0.5 * a;
  over_probe.dy = a;
  over_probe.nx = over_probe.ny = 1;

  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  ns::Simulation<Dim> sim(std::move(particles), s, lower, upper);
  auto measure = [&](bool solved) {
    const auto& p = sim.particles();
    Record r;
    r.T = sim.time() / time_scale_s;
    r.Z = ns::front_position<Dim>(p, l0) / a;
    r.h_floor = ns::column_depth<Dim>(p, l0, over_probe)[0] / a;
    r.fluid = p.fluid;
    if (!solved) {
      r.p_floor = r.p_wall = std::numeric_limits<double>::quiet_NaN();
      return r;
    }
    r.p_floor = ns::pressure_at<Dim>(p, sim.pressure_kernel(), floor_probe) / pressure_scale_pa;
    r.p_wall = ns::pressure_at<Dim>(p, sim.pressure_kernel(), wall_probe) / pressure_scale_pa;
    r.dt_s = sim.last_step().time_step_s;
    r.iterations = sim.last_step().poisson.iterations;
    r.residual = sim.last_step().poisson.relative_residual;
    return r;
  };
  result.records.push_back(measure(false));
  const double end_s = o.end_T * time_scale_s;
  try {
    // Every step is the solver's stable step. advance_to would cut the step before each
    // sample time to land on it, and a cut step's pressure is not like the others': the
    // source scales as 1/dt^2 times a density error that a shorter step barely changes.
    // Samples are taken from the steps around each sample time instead. With
    // --land-on-samples the run lands on every sample time with advance_to and records only
    // there, to show the difference (docs/ns-dam-break.md).
    const double sample_s = o.interval_T * time_scale_s;
    while (sim.time() < end_s) {
      if (o.land_on_samples) {
        sim.advance_to((std::lround(sim.time() / sample_s) + 1) * sample_s);
      } else {
        sim.advance(sim.stable_time_step());
      }
      result.records.push_back(measure(true));
    }
  } catch (const std::runtime_error& e) {
    // SimulationError, or the Poisson solver's own failure (an incomplete Cholesky factor
    // that cannot be formed): either way the run broke down, and what it recorded until
    // then is still written.
    std::ostringstream why;
    why << "broke down at T = " << sim.time() / time_scale_s << " (step " << sim.steps() + 1
        << "): " << e.what();
    result.failure = why.str();
  }
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.cpu_time_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  result.totals = sim.totals();
  return result;
}

std::string kernel_label(const ns::KernelChoice& k) {
  std::ostringstream out;
  out << kernels::kernel_type_name(k.spec.type) << "/" << k.support_spacings;
  if (k.spec.type == kernels::KernelType::hyperbolic_mps ||
      k.spec.type == kernels::KernelType::hyperbolic_sph) {
    out << "/kappa" << k.spec.kappa;
  }
  return out.str();
}

std::ofstream open_csv(const std::string& path, const Options& o) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.precision(8);
  out << "# " << o.command_line << "\n";
  out << "# T = t sqrt(2g/a); Z = front / a; pressures / (rho g a); h_floor: depth over the "
         "floor probe / a; p_floor_average: centred mean over T +- "
      << 0.5 * noise_window << "\n";
  return out;
}

// One row per sample time T_k: the front interpolated at T_k, everything else from the first
// step that ends at or after T_k; iterations are the mean per step since the row before.
void write_samples(const Options& o, const Run& r, const std::string& summary) {
  std::ofstream out = open_csv(o.output, o);
  const auto average = centred_average(r.records, &Record::p_floor);
  out << "T,Z,p_floor,p_floor_average,p_wall,h_floor,dt_s,steps,iterations,residual,fluid\n";
  std::size_t previous = 0;
  for (long k = 0;; ++k) {
    const double T = k * o.interval_T;
    if (T > o.end_T + 1e-9 || T > r.records.back().T + 1e-9) break;
    const auto it = std::lower_bound(r.records.begin(), r.records.end(), T - 1e-9,
                                     [](const Record& rec, double t) { return rec.T < t; });
    const auto j = static_cast<std::size_t>(it - r.records.begin());
    double iterations = 0.0;
    for (std::size_t m = previous + 1; m <= j; ++m) iterations += r.records[m].iterations;
    if (j > previous) iterations /= static_cast<double>(j - previous);
    const Record& rec = r.records[j];
    out << T << "," << front_at(r.records, T) << "," << rec.p_floor << "," << average[j] << ","
        << rec.p_wall << "," << rec.h_floor << "," << rec.dt_s << "," << j << "," << iterations
        << "," << rec.residual << "," << rec.fluid << "\n";
    previous = j;
  }
  out << "# summary: " << summary << "\n";
}

void write_steps(const Options& o, const Run& r) {
  std::ofstream out = open_csv(o.steps_output, o);
  const auto average = centred_average(r.records, &Record::p_floor);
  out << "T,Z,p_floor,p_floor_average,p_wall,h_floor,dt_s,iterations,residual,fluid\n";
  for (std::size_t k = 0; k < r.records.size(); ++k) {
    const Record& rec = r.records[k];
    out << rec.T << "," << rec.Z << "," << rec.p_floor << "," << average[k] << "," << rec.p_wall
        << "," << rec.h_floor << "," << rec.dt_s << "," << rec.iterations << "," << rec.residual
        << "," << rec.fluid << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::invalid_argument& e) {
    if (*e.what()) std::fprintf(stderr, "swemps-ns-dam-break: %s\n\n", e.what());
    std::fputs(usage, stderr);
    return 2;
  }
  if (o.threads > 0) omp_set_num_threads(o.threads);

  Run r;
  std::vector<ExperimentPoint> experiment;
  try {
    experiment = read_experiment(o.data);
    r = o.dim == 2 ? run<2>(o) : run<3>(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swemps-ns-dam-break: %s\n", e.what());
    return 1;
  }

  const FrontError all = front_error(r.records, experiment, 0.0);
  const FrontError late = front_error(r.records, experiment, late_from);
  const double floor_noise = rms_noise(r.records, &Record::p_floor);
  const double wall_noise = rms_noise(r.records, &Record::p_wall);
  const double half_spacing = 0.5 / o.resolution;
  const double floor_early = mean_pressure(r.records, &Record::p_floor, 0.0, early_to);
  const double wall_early = mean_pressure(r.records, &Record::p_wall, 0.0, early_to);
  const double late_ratio = over_hydrostatic(r.records, noise_from, noise_to, half_spacing);
  const auto& t = r.totals;
  const double steps = std::max<double>(1.0, static_cast<double>(t.steps));
  const auto& ph = t.phases;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();

  std::ostringstream summary;
  summary.precision(4);
  summary << "dim=" << o.dim << " resolution=" << o.resolution
          << " pressure_kernel=" << kernel_label(o.settings.pressure_kernel)
          << " velocity_kernel=" << kernel_label(o.settings.velocity_kernel)
          << " source=" << (o.settings.source == ns::SourceTerm::mixed ? "mixed" : "number-density")
          << " beta=" << o.settings.free_surface_beta
          << " asymmetry=" << o.settings.free_surface_asymmetry << " gradient="
          << (o.settings.gradient == ns::PressureGradient::corrected ? "corrected"
              : o.settings.gradient == ns::PressureGradient::corrected_repulsive
                  ? "corrected-repulsive"
                  : "minimum-pressure")
          << " gradient_weights=" << ns::gradient_weights_name(o.settings.gradient_weights)
          << " boundary="
          << (o.settings.boundary == ns::BoundaryPressure::extrapolated ? "extrapolated"
                                                                        : "poisson")
          << " operators="
          << (o.settings.operators == ns::Operators::least_squares ? "least-squares" : "mps")
          << " collision=" << (o.settings.collision ? "on" : "off") << " threads=" << threads
          << " fluid=" << r.fluid << " wall=" << r.wall << " dummy=" << r.dummy
          << " layers=" << r.solid_layers << " steps=" << t.steps
          << " reached_T=" << r.records.back().T << " wall_time_s=" << r.wall_time_s
          << " cpu_time_s=" << r.cpu_time_s << " poisson_mean=" << t.poisson_iterations / steps
          << " poisson_max=" << t.max_poisson_iterations << " unconverged=" << t.unconverged_solves
          << " lost=" << t.lost_particles << " Z_err_mean=" << all.mean << " Z_err_max=" << all.max
          << " points=" << all.points << " Z_err_mean_T>=1=" << late.mean
          << " Z_err_max_T>=1=" << late.max << " points_T>=1=" << late.points
          << " floor_noise=" << floor_noise << " wall_noise=" << wall_noise
          << " floor_mean_early=" << floor_early << " wall_mean_early=" << wall_early
          << " floor_over_hydrostatic_late=" << late_ratio << " phase_s=sort:" << ph.sort
          << ",neighbours:" << ph.neighbors << ",explicit:" << ph.explicit_part
          << ",density:" << ph.density << ",assembly:" << ph.assembly << ",solve:" << ph.solve
          << ",correction:" << ph.correction;
  if (!r.failure.empty()) summary << " FAILED: " << r.failure;
  std::printf("%s\n", summary.str().c_str());

  try {
    write_samples(o, r, summary.str());
    if (!o.steps_output.empty()) write_steps(o, r);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swemps-ns-dam-break: %s\n", e.what());
    return 1;
  }
  return r.failure.empty() ? 0 : 3;
}
