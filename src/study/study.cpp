#include "swemps/study/study.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace swemps::study {

namespace {

// One axis of the product: the knob values it contributes, as setters on RunKnobs. An axis
// that is not swept contributes one setter that changes nothing, so it multiplies by 1.
template <class Value, class Setter>
std::vector<std::function<void(RunKnobs&)>> axis(const std::vector<Value>& values, Setter set) {
  if (values.empty()) return {[](RunKnobs&) {}};
  std::vector<std::function<void(RunKnobs&)>> out;
  for (const Value& v : values) out.push_back([v, set](RunKnobs& k) { set(k, v); });
  return out;
}

std::string number_text(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}

}  // namespace

std::vector<RunKnobs> expand(const Sweep& sweep, swe::SchemeKind scene_scheme) {
  // Slowest first: spacing varies least often, so neighbouring rows differ in the cheap knobs.
  const std::vector<std::vector<std::function<void(RunKnobs&)>>> axes{
      axis(sweep.spacing_m, [](RunKnobs& k, double v) { k.spacing_m = v; }),
      axis(sweep.splitting, [](RunKnobs& k, SplittingChoice v) { k.splitting = v; }),
      axis(sweep.scheme, [](RunKnobs& k, swe::SchemeKind v) { k.scheme = v; }),
      axis(sweep.gradient, [](RunKnobs& k, swe::GradientVariant v) { k.gradient = v; }),
      axis(sweep.kappa, [](RunKnobs& k, double v) { k.kappa = v; }),
      axis(sweep.dissipation, [](RunKnobs& k, double v) { k.dissipation = v; }),
      axis(sweep.shifting, [](RunKnobs& k, double v) { k.shifting = v; }),
      axis(sweep.cfl, [](RunKnobs& k, double v) { k.cfl = v; }),
      axis(sweep.alpha_e, [](RunKnobs& k, double v) { k.alpha_e = v; }),
  };
  std::vector<RunKnobs> runs{RunKnobs{}};
  for (const auto& setters : axes) {
    std::vector<RunKnobs> longer;
    longer.reserve(runs.size() * setters.size());
    for (const RunKnobs& run : runs) {
      for (const auto& set : setters) {
        RunKnobs k = run;
        set(k);
        longer.push_back(k);
      }
    }
    runs = std::move(longer);
  }
  // A scheme's own knobs mean nothing to the other scheme (the scene loader refuses them
  // there): drop them from its runs, then keep the first of any runs that became equal.
  bool seed_runs = false, conservative_runs = false;
  std::vector<RunKnobs> kept;
  for (RunKnobs k : runs) {
    if (k.scheme.value_or(scene_scheme) == swe::SchemeKind::seed) {
      seed_runs = true;
      k.kappa.reset();
      k.dissipation.reset();
      k.shifting.reset();
    } else {
      conservative_runs = true;
      k.gradient.reset();
      k.alpha_e.reset();
    }
    if (std::find(kept.begin(), kept.end(), k) == kept.end()) kept.push_back(k);
  }
  const auto require = [](bool used, const auto& axis_values, const char* knob,
                          const char* scheme) {
    if (!axis_values.empty() && !used) {
      throw std::invalid_argument(std::string("\"") + knob + "\", a knob of the " + scheme +
                                  " scheme, which no run uses");
    }
  };
  require(seed_runs, sweep.gradient, "gradient", "seed");
  require(seed_runs, sweep.alpha_e, "alpha_e", "seed");
  require(conservative_runs, sweep.kappa, "kappa", "conservative");
  require(conservative_runs, sweep.dissipation, "dissipation", "conservative");
  require(conservative_runs, sweep.shifting, "shifting", "conservative");
  return kept;
}

void apply(const RunKnobs& knobs, scenario::Scenario& scene) {
  if (knobs.spacing_m) {
    for (auto& body : scene.water) body.spacing_m = *knobs.spacing_m;
    for (auto& inflow : scene.inflows) inflow.spacing_m = *knobs.spacing_m;
  }
  if (knobs.splitting) {
    if (const auto threshold = knobs.splitting->area_ratio_threshold) {
      splitting::SplittingSettings settings =
          scene.splitting.value_or(splitting::SplittingSettings{});
      settings.area_ratio_threshold = *threshold;
      scene.splitting = settings;
    } else {
      scene.splitting.reset();
    }
  }
  if (knobs.scheme) scene.numerics.scheme = *knobs.scheme;
  if (knobs.gradient) scene.numerics.gradient = *knobs.gradient;
  if (knobs.kappa) scene.numerics.kappa = *knobs.kappa;
  if (knobs.dissipation) scene.numerics.dissipation = *knobs.dissipation;
  if (knobs.shifting) scene.numerics.shifting = *knobs.shifting;
  if (knobs.cfl) scene.numerics.cfl = *knobs.cfl;
  if (knobs.alpha_e) scene.numerics.alpha_e = *knobs.alpha_e;
}

double finest_spacing(const scenario::Scenario& scene) {
  double finest = 0.0;
  const auto take = [&](double spacing) {
    if (spacing > 0.0 && (finest == 0.0 || spacing < finest)) finest = spacing;
  };
  for (const auto& body : scene.water) take(body.spacing_m);
  for (const auto& inflow : scene.inflows) take(inflow.spacing_m);
  return finest;
}

RunMeasures measure(const swe::Simulation& simulation, const scenario::Scenario& scene,
                    const RitterReference& reference, double profile_spacing_ratio) {
  const auto& d = scene.domain;
  const double dx_m = finest_spacing(scene) / profile_spacing_ratio;
  const verification::Profile profile = verification::channel_profile(
      simulation.particles(), simulation.kernel(), {d.x_min, d.x_max, d.y_min, d.y_max}, dx_m);
  const verification::RitterProblem problem{reference.dam_x_m, reference.initial_depth_m,
                                            scene.numerics.gravity_m_s2,
                                            reference.reservoir_start_x_m};
  RunMeasures m;
  m.particles_end = simulation.particles().fluid_count();
  m.steps = simulation.steps();
  m.particle_steps = simulation.particle_steps();
  m.relative_volume_change = simulation.relative_volume_change();
  m.errors = verification::compare_with_ritter(problem, profile, simulation.time());
  return m;
}

std::vector<std::size_t> pareto_front(const std::vector<CostError>& runs) {
  const auto finite = [](const CostError& r) {
    return std::isfinite(r.cost) && std::isfinite(r.error);
  };
  const auto beats = [](const CostError& a, const CostError& b) {
    return a.cost <= b.cost && a.error <= b.error && (a.cost < b.cost || a.error < b.error);
  };
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!finite(runs[i])) continue;
    const bool beaten = std::any_of(runs.begin(), runs.end(), [&](const CostError& other) {
      return finite(other) && beats(other, runs[i]);
    });
    if (!beaten) front.push_back(i);
  }
  std::stable_sort(front.begin(), front.end(),
                   [&](std::size_t a, std::size_t b) { return runs[a].cost < runs[b].cost; });
  return front;
}

std::string gradient_name(swe::GradientVariant gradient) {
  return gradient == swe::GradientVariant::summation ? "summation" : "mps";
}

std::string scheme_name(swe::SchemeKind scheme) {
  return scheme == swe::SchemeKind::seed ? "seed" : "conservative";
}

std::string describe(const RunKnobs& knobs) {
  std::vector<std::string> parts;
  if (knobs.spacing_m) parts.push_back("spacing " + number_text(*knobs.spacing_m) + " m");
  if (knobs.splitting) {
    const auto threshold = knobs.splitting->area_ratio_threshold;
    parts.push_back("splitting " + (threshold ? number_text(*threshold) : std::string("off")));
  }
  if (knobs.scheme) parts.push_back(scheme_name(*knobs.scheme));
  if (knobs.gradient) parts.push_back(gradient_name(*knobs.gradient));
  if (knobs.kappa) parts.push_back("kappa " + number_text(*knobs.kappa));
  if (knobs.dissipation) parts.push_back("dissipation " + number_text(*knobs.dissipation));
  if (knobs.shifting) parts.push_back("shifting " + number_text(*knobs.shifting));
  if (knobs.cfl) parts.push_back("cfl " + number_text(*knobs.cfl));
  if (knobs.alpha_e) parts.push_back("alpha_e " + number_text(*knobs.alpha_e));
  if (parts.empty()) return "the scene as it is";
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i > 0 ? ", " : "") + parts[i];
  return out;
}

}  // namespace swemps::study
