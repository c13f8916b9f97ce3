#include "swemps/cli/run_command.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>

#include <filesystem>

#include "swemps/cli/check_command.hpp"
#include "swemps/cli/compare_command.hpp"
#include "swemps/cli/ensemble_command.hpp"
#include "swemps/cli/export_command.hpp"
#include "swemps/cli/log_file.hpp"
#include "swemps/cli/output_target.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/cli/study_command.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

void run(const Options& options, const std::string& command_line) {
  if (options.command == "compare") {
    compare(options, command_line);
    return;
  }
  if (options.command == "study") {
    study(options, command_line);
    return;
  }
  if (options.command == "ensemble") {
    ensemble(options, command_line);
    return;
  }
  if (options.command == "check") {
    check(options, command_line);
    return;
  }
  if (options.command == "export") {
    export_products(options);
    return;
  }
  auto scene = scenario::load(options.scenario);
  if (options.output) scene.output.path = output_option(*options.output);
  check_output_target(scene.output.path);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const RunContext context = run_context(options, command_line, scene);
  keep_log_beside(scene.output.path, options.restart.has_value());
  spdlog::info("{}", command_line);
  if (scene.model == scenario::Model::ns) {
    run_ns(scene, context);
  } else {
    run_swe(scene, context);
  }
}

}  // namespace swemps::cli
