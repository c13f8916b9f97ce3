#pragma once
// The log a run keeps beside its output (OUTPUT.log): every message at debug level, with the
// time, whatever the terminal shows, so that a batch run keeps its story.

#include <filesystem>
#include <string>

namespace swemps::cli {

// The log file of a run writing `output`: the same path with the extension .log.
std::filesystem::path log_path(const std::filesystem::path& output);

// Adds the log file to the default logger, from here on; `append` goes on with the file a run
// stopped early left (a restarted run), else it starts empty. Throws OutputError when the file
// cannot be opened.
void keep_log_beside(const std::filesystem::path& output, bool append);

// Writes the line that ends a failed run (the one the terminal gets on its own) into the log
// file, if the run keeps one, so that the log says how the run ended.
void log_failure(const std::string& line);

}  // namespace swemps::cli
