#include "swemps/cli/options.hpp"

#include <algorithm>
#include <charconv>

namespace swemps::cli {

std::string usage_text() {
  return R"(swe-mps: shallow-water MPS particle simulator for floods and tsunamis

Usage:
  swe-mps run SCENARIO.json [options]
  swe-mps compare SCENARIO.json [options]
  swe-mps study STUDY.json [options]
  swe-mps check SCENARIO.json [options]
  swe-mps export RESULT.nc [--maps LIST] [--format cog|geotiff] [-o PREFIX]
  swe-mps --help | --version

Commands:
  run       run the scene with its model: shallow water, or Navier-Stokes ("model": "ns")
  compare   run the scene as shallow water and as 3D Navier-Stokes (its "ns" block) and
            write both maps, the Navier-Stokes series and both surge fronts beside
            Ritter's: STEM.swe.nc, STEM.ns.nc, STEM.ns.series.csv, STEM.fronts.csv
  study     run a scene once for every combination of the numerical knobs a study file
            lists (spacing, splitting, scheme, gradient, kappa, dissipation, shifting,
            cfl, alpha_e), each in its own process, and tabulate each run's cost and
            its error against Ritter's solution (CSV)
  check     everything a run checks before its first step, and a report: the domain, the
            CRS, each raster's extent, cells, range and nodata, the particles, the memory,
            the first time step and an estimate of the run's wall time; nothing is written
  export    from a run's netCDF result: GeoTIFF maps of its whole-run statistics and
            hazard classes (PREFIX_<map>.tif, PREFIX the result without .nc) and the gauge
            series as CSV (PREFIX_gauges.csv)

Options:
  -o, --output PATH   run: write the netCDF result to PATH instead of the scene's
                      output.path; compare: the STEM of its files (default: output.path
                      without its extension); study: the CSV table (default: the study
                      file's output)
  -t, --threads N     OpenMP threads (default: all cores; results do not depend on N);
                      study: threads per run (default: cores / jobs)
  -j, --jobs N        study: runs at once (default: the study file's jobs, or one per core)
      --checkpoint-every N
                      run: also write a checkpoint every N output times
                      (one is always written when the run stops early); the checkpoint is
                      the output path with the extension .checkpoint
      --restart FILE  run: go on from checkpoint FILE, written by a run of
                      the same scenario file, writing on into the output that run left
                      (OUTPUT.partial); the result is the same as one run straight through
      --maps LIST     export: the maps to write, comma-separated, or "all" (the default);
                      see docs/outputs.md for the names
      --format F      export: "cog" (Cloud-Optimised GeoTIFF, the default) or "geotiff"
  -q, --quiet         warnings and errors only, no progress
  -v, --verbose       debug messages
  -h, --help          this text
      --version       print the version

Exit status: 0 done; 2 bad command line, scenario or checkpoint; 3 the simulation broke
down (non-finite values or a collapsing time step: the last good state is written to
OUTPUT.partial, with a checkpoint); 4 the output could not be written; 130 or 143
stopped by SIGINT or SIGTERM (128 + the signal: the state after the current step is
written to OUTPUT.partial, with a checkpoint; a second signal stops at once); 1 any
other error.
)";
}

namespace {

// A whole number from 1 to `largest`, the value of option `name`.
int parse_count(const std::string& name, const std::string& text, int largest = 1024) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 1 || value > largest) {
    throw UsageError(name + " expects a whole number from 1 to " + std::to_string(largest) +
                     ", found '" + text + "'");
  }
  return value;
}

}  // namespace

Options parse_options(const std::vector<std::string>& args) {
  Options options;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& arg = args[k];
    auto value = [&](const std::string& name) -> const std::string& {
      if (k + 1 >= args.size()) throw UsageError(name + " expects a value");
      return args[++k];
    };
    if (arg == "-h" || arg == "--help") {
      options.command = "help";
      return options;
    } else if (arg == "--version") {
      options.command = "version";
      return options;
    } else if (arg == "-o" || arg == "--output") {
      options.output = value(arg);
    } else if (arg == "-t" || arg == "--threads") {
      options.threads = parse_count("--threads", value(arg));
    } else if (arg == "-j" || arg == "--jobs") {
      options.jobs = parse_count("--jobs", value(arg));
    } else if (arg == "--checkpoint-every") {
      options.checkpoint_every = parse_count(arg, value(arg), 1'000'000);
    } else if (arg == "--restart") {
      options.restart = value(arg);
    } else if (arg == "--maps") {
      options.maps.clear();
      const std::string& list = value(arg);
      std::size_t start = 0;
      while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        if (comma > start) options.maps.push_back(list.substr(start, comma - start));
        start = comma + 1;
      }
      if (options.maps.empty()) throw UsageError("--maps expects a list of map names");
    } else if (arg == "--format") {
      options.format = value(arg);
      if (options.format != "cog" && options.format != "geotiff") {
        throw UsageError("--format expects 'cog' or 'geotiff', found '" + options.format + "'");
      }
    } else if (arg == "-q" || arg == "--quiet") {
      options.verbosity = Verbosity::quiet;
    } else if (arg == "-v" || arg == "--verbose") {
      options.verbosity = Verbosity::verbose;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' (see swe-mps --help)");
    } else if (options.command.empty()) {
      if (arg != "run" && arg != "compare" && arg != "study" && arg != "check" && arg != "export") {
        throw UsageError("unknown command '" + arg +
                         "' (the commands are: run, compare, study, check, export)");
      }
      options.command = arg;
    } else if (options.scenario.empty()) {
      options.scenario = arg;
    } else {
      throw UsageError("unexpected argument '" + arg + "'");
    }
  }
  if (options.command.empty()) throw UsageError("no command given (see swe-mps --help)");
  if (options.command != "run" && (options.restart || options.checkpoint_every > 0)) {
    throw UsageError("--restart and --checkpoint-every apply to 'run' only");
  }
  if (options.command != "export" && (!options.maps.empty() || !options.format.empty())) {
    throw UsageError("--maps and --format apply to 'export' only");
  }
  if (options.scenario.empty()) {
    throw UsageError("'" + options.command + "' expects a " +
                     (options.command == "study"    ? "study file"
                      : options.command == "export" ? "netCDF result of a run"
                                                    : "scenario file"));
  }
  return options;
}

}  // namespace swemps::cli
