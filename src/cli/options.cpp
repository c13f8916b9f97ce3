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
  swe-mps ensemble ENSEMBLE.json [--member N | --plan | --collect | --submit] [options]
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
  ensemble  run a base scene once per member of an ensemble file (values put into the
            scene by JSON pointer: lists, or sampled ranges with a seed), each member a
            `swe-mps run` of its own scene in its own folder, and combine the members'
            maximum depths: the probability of exceeding each depth threshold, the mean and
            the envelope (netCDF and GeoTIFF), with a CSV of the members. Without a mode
            option the members run on this machine, --jobs at once; --submit runs them as
            a Slurm job array with a collection job after it; --member N runs one member
            (for any other scheduler); --plan writes the members' scenes; --collect makes
            the products of the members that ran (docs/ensembles.md)
  check     everything a run checks before its first step, and a report: the domain, the
            CRS, each raster's extent, cells, range and nodata, the particles, the memory,
            the first time step and an estimate of the run's wall time with its band (the
            scene and a coarser pilot stepped in memory, 35 s at most); nothing is
            written
  export    from a run's netCDF result: GeoTIFF maps of its whole-run statistics and
            hazard classes (PREFIX_<map>.tif, PREFIX the result without .nc) and the gauge
            series as CSV (PREFIX_gauges.csv); from a run with tsunami maps also the
            inundation line (PREFIX_inundation_line.gpkg) and the gauge arrivals
            (PREFIX_gauge_arrivals.csv)

Options:
  -o, --output PATH   run: write the netCDF result to PATH instead of the scene's
                      output.path; compare: the STEM of its files (default: output.path
                      without its extension); study: the CSV table (default: the study
                      file's output); ensemble: the folder of the members and products
                      (default: the ensemble file's "folder")
  -t, --threads N     OpenMP threads (default: all cores; results do not depend on N);
                      study: threads per run (default: cores / jobs); ensemble: threads
                      per member (default: the file's threads_per_member, or 1)
  -j, --jobs N        study, ensemble: runs at once (default: the file's jobs, or one per
                      core; an ensemble: cores / threads per member)
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
      --member N      ensemble: run member N (from 0) alone; its exit status is its run's
      --plan          ensemble: write every member's scene and the members table, run nothing
      --collect       ensemble: the products of the members that ran (every member must
                      have finished, unless --partial)
      --submit        ensemble: submit the members as a Slurm job array (at most
                      --max-running at once) and a collection job that waits for them
      --failed-only   ensemble: run (or submit) only the members without a finished run
      --partial       ensemble: make the products from the members that finished even when
                      others did not (the files say which were combined)
      --partition P, --account A, --time T, --memory M, --max-running N
                      ensemble --submit: sbatch settings over the ensemble file's "slurm"
                      (--time and --memory per member, as sbatch takes them: 2:00:00, 4G)
  -q, --quiet         warnings and errors only, no progress
  -v, --verbose       debug messages
  -h, --help          this text
      --version       print the version

Exit status: 0 done; 2 bad command line, scenario, study, ensemble or checkpoint; 3 the
simulation broke
down (non-finite values or a collapsing time step: the last good state is written to
OUTPUT.partial, with a checkpoint); 4 the output could not be written; 130 or 143
stopped by SIGINT or SIGTERM (128 + the signal: the state after the current step is
written to OUTPUT.partial, with a checkpoint; a second signal stops at once); 5 an
ensemble some of whose members did not finish (its members table says which and why); 1 any
other error. `ensemble --member N` exits as the member's run did.
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

// A whole number from 0, the value of option `name`.
std::size_t parse_index(const std::string& name, const std::string& text) {
  std::size_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
    throw UsageError(name + " expects a whole number from 0, found '" + text + "'");
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
    } else if (arg == "--member") {
      options.member = parse_index(arg, value(arg));
    } else if (arg == "--plan") {
      options.plan = true;
    } else if (arg == "--collect") {
      options.collect = true;
    } else if (arg == "--submit") {
      options.submit = true;
    } else if (arg == "--failed-only") {
      options.failed_only = true;
    } else if (arg == "--partial") {
      options.partial = true;
    } else if (arg == "--partition" || arg == "--account" || arg == "--time" || arg == "--memory") {
      const std::string& text = value(arg);
      if (text.empty() || text.find_first_of(" \t\n\r'\"\\$`") != std::string::npos) {
        throw UsageError(arg + " expects a value without blanks or quotes, found '" + text + "'");
      }
      (arg == "--partition" ? options.partition
       : arg == "--account" ? options.account
       : arg == "--time"    ? options.time_limit
                            : options.memory) = text;
    } else if (arg == "--max-running") {
      options.max_running = parse_count(arg, value(arg), 100'000);
    } else if (arg == "-q" || arg == "--quiet") {
      options.verbosity = Verbosity::quiet;
    } else if (arg == "-v" || arg == "--verbose") {
      options.verbosity = Verbosity::verbose;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' (see swe-mps --help)");
    } else if (options.command.empty()) {
      if (arg != "run" && arg != "compare" && arg != "study" && arg != "ensemble" &&
          arg != "check" && arg != "export") {
        throw UsageError("unknown command '" + arg +
                         "' (the commands are: run, compare, study, ensemble, check, export)");
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
  const int modes = (options.member ? 1 : 0) + (options.plan ? 1 : 0) + (options.collect ? 1 : 0) +
                    (options.submit ? 1 : 0);
  const bool slurm_settings = !options.partition.empty() || !options.account.empty() ||
                              !options.time_limit.empty() || !options.memory.empty() ||
                              options.max_running;
  if (options.command != "ensemble" &&
      (modes > 0 || options.failed_only || options.partial || slurm_settings)) {
    throw UsageError(
        "--member, --plan, --collect, --submit, --failed-only, --partial, --partition, "
        "--account, --time, --memory and --max-running apply to 'ensemble' only");
  }
  if (modes > 1) {
    throw UsageError("--member, --plan, --collect and --submit are modes: give one at most");
  }
  if (options.failed_only && (options.member || options.plan || options.collect)) {
    throw UsageError("--failed-only applies to running the members (no mode) or --submit");
  }
  if (options.partial && (options.member || options.plan)) {
    throw UsageError("--partial applies to collecting the products (no mode, or --collect)");
  }
  if (slurm_settings && !options.submit) {
    throw UsageError(
        "--partition, --account, --time, --memory and --max-running apply to --submit");
  }
  if (options.scenario.empty()) {
    throw UsageError("'" + options.command + "' expects a " +
                     (options.command == "study"      ? "study file"
                      : options.command == "ensemble" ? "ensemble file"
                      : options.command == "export"   ? "netCDF result of a run"
                                                      : "scenario file"));
  }
  return options;
}

}  // namespace swemps::cli
