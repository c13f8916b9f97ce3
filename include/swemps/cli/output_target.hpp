#pragma once
// Whether a run can write its output file, found out before the run starts: a folder that is
// missing or is a file, a target that is a folder, or a folder that refuses new files would
// otherwise be reported only when the first map is written, after the rasters are read and the
// particles seeded, or (a target that is a folder) after the whole run, when the finished file
// is renamed into place.

#include <filesystem>
#include <string>

namespace swemps::cli {

// Throws OutputError, one line naming `file` and what is in the way. Missing folders are not
// created: a mistyped folder should be reported, not made. The folder is tested by creating
// the file's <file>.partial, which the writer creates first anyway, and removing it again
// unless it was there before; so a read-only file system or a folder without write permission
// is found out even for a user (root) whom permission bits do not stop.
void check_output_target(const std::filesystem::path& file);

// The path given with -o, absolute and normalised; an empty one stays empty, for
// check_output_target to report (std::filesystem::absolute throws on it).
std::filesystem::path output_option(const std::filesystem::path& given);

// Writes `text` to `file` under <file>.partial first and renames it into place, so that a
// reader never sees half a file. Throws OutputError naming the file.
void write_whole_file(const std::filesystem::path& file, const std::string& text);

}  // namespace swemps::cli
