// swe-mps: entry point. Turns every failure into one clear line and an exit status.

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "swemps/cli/log_file.hpp"
#include "swemps/cli/options.hpp"
#include "swemps/cli/run_command.hpp"
#include "swemps/io/checkpoint.hpp"
#include "swemps/io/gdal_messages.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/simulation.hpp"

namespace {

void set_up_logging(swemps::cli::Verbosity verbosity) {
  auto logger = spdlog::stderr_color_mt("swe-mps");
  logger->set_pattern("%^[%l]%$ %v");
  // The terminal shows what the verbosity asks for; the logger passes everything on, for the
  // log file a run keeps beside its output (swemps::cli::keep_log_beside).
  logger->set_level(spdlog::level::debug);
  const auto& terminal = logger->sinks().front();
  switch (verbosity) {
    case swemps::cli::Verbosity::quiet: terminal->set_level(spdlog::level::warn); break;
    case swemps::cli::Verbosity::normal: terminal->set_level(spdlog::level::info); break;
    case swemps::cli::Verbosity::verbose: terminal->set_level(spdlog::level::debug); break;
  }
  spdlog::set_default_logger(logger);
  // What GDAL reports outside the readers' own checks (the readers fold its errors into
  // theirs) joins the log instead of appearing as its own "ERROR 1:" lines.
  swemps::io::send_gdal_messages_to([](bool is_error, std::string_view message) {
    const std::string line = swemps::scenario::printable_line(message);
    if (is_error) {
      spdlog::warn("GDAL: {}", line);
    } else {
      spdlog::debug("GDAL: {}", line);
    }
  });
}

// One line: a file name or key with a line break in it cannot split the message.
int fail(int status, const std::string& message) {
  const std::string line = swemps::scenario::printable_line(message);
  std::fprintf(stderr, "swe-mps: %s\n", line.c_str());
  swemps::cli::log_failure(line + " (exit status " + std::to_string(status) + ")");
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace swemps::cli;
  const std::vector<std::string> args(argv + 1, argv + argc);
  std::string command_line = "swe-mps";
  for (const auto& a : args) command_line += " " + a;

  Options options;
  try {
    options = parse_options(args);
  } catch (const UsageError& e) {
    fail(exit_input, e.what());
    std::fprintf(stderr, "\n%s", usage_text().c_str());
    return exit_input;
  }
  if (options.command == "help") {
    std::fputs(usage_text().c_str(), stdout);
    return exit_ok;
  }
  if (options.command == "version") {
    std::printf("swe-mps %s\n", SWEMPS_VERSION);
    return exit_ok;
  }

  set_up_logging(options.verbosity);
  try {
    run(options, command_line);
    return exit_ok;
  } catch (const swemps::scenario::ScenarioError& e) {
    return fail(exit_input, e.what());
  } catch (const UsageError& e) {
    return fail(exit_input, e.what());
  } catch (const swemps::io::CheckpointError& e) {
    return fail(exit_input, std::string("cannot restart: ") + e.what());
  } catch (const CommandFailed& e) {
    return fail(e.status(), e.what());
  } catch (const RunStopped& e) {
    return fail(exit_signal + e.signal_number(), e.what());
  } catch (const swemps::swe::SimulationError& e) {
    return fail(exit_breakdown, std::string("the simulation broke down: ") + e.what());
  } catch (const swemps::ns::SimulationError& e) {
    return fail(exit_breakdown, std::string("the simulation broke down: ") + e.what());
  } catch (const OutputError& e) {
    return fail(exit_output, std::string("cannot write output: ") + e.what());
  } catch (const std::bad_alloc&) {
    // The scene's memory is checked before the run starts; this is a scene that grew (by
    // splitting, say) or a machine whose memory others took meanwhile.
    return fail(exit_internal,
                "out of memory: the run needed more memory than it could get (a coarser "
                "spacing, a lower splitting.max_particles, or a machine with more memory)");
  } catch (const std::exception& e) {
    return fail(exit_internal, std::string("error: ") + e.what());
  }
}
