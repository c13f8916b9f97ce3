#pragma once
// `swe-mps study`: an accuracy-cost sweep (study/study.hpp). Every combination of the knobs a
// study file lists runs in its own child process, so that each run's peak memory is its own
// and a run that crashes or breaks down costs only its row. A CSV table gets one row per run,
// in the order of the sweep, and the closing summary lists the Pareto front of wall time
// against the error: the fan's L1 error against Ritter's solution, or the maximum depth's mean
// absolute difference against a reference map (each run then writes its own result file,
// which the parent measures: cli/study_reference.hpp).

#include <string>

#include "swemps/cli/options.hpp"

namespace swemps::cli {

// Runs the study file options.scenario and writes its table (-o, or the file's output):
// rows are rewritten into <table>.partial as runs finish, and the file gets its final name
// when the last has. A run that breaks down or fails is a row with its status and message;
// the study goes on. Throws scenario::ScenarioError (the study file, or the scene it names),
// OutputError.
void study(const Options& options, const std::string& command_line);

}  // namespace swemps::cli
