#include "swemps/cli/log_file.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include "swemps/cli/run_command.hpp"

namespace swemps::cli {

std::filesystem::path log_path(const std::filesystem::path& output) {
  std::filesystem::path path = output;
  path.replace_extension(".log");
  return path;
}

void keep_log_beside(const std::filesystem::path& output, bool append) {
  const std::filesystem::path path = log_path(output);
  std::shared_ptr<spdlog::sinks::basic_file_sink_mt> file;
  try {
    file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path.string(), !append);
  } catch (const spdlog::spdlog_ex& e) {
    throw OutputError("cannot write the log file '" + path.string() + "': " + e.what());
  }
  file->set_level(spdlog::level::debug);
  file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
  // Messages go to every sink of the logger; the file is flushed at each so that a run killed
  // outright keeps its log to the last line.
  const auto logger = spdlog::default_logger();
  // One log file at a time: a second run in the same process writes its own.
  auto& sinks = logger->sinks();
  std::erase_if(sinks, [](const spdlog::sink_ptr& s) {
    return dynamic_cast<spdlog::sinks::basic_file_sink_mt*>(s.get()) != nullptr;
  });
  sinks.push_back(file);
  logger->flush_on(spdlog::level::debug);
}

void log_failure(const std::string& line) {
  for (const auto& sink : spdlog::default_logger()->sinks()) {
    if (dynamic_cast<spdlog::sinks::basic_file_sink_mt*>(sink.get()) == nullptr) continue;
    spdlog::logger("failure", sink).error("{}", line);
    sink->flush();
  }
}

}  // namespace swemps::cli
