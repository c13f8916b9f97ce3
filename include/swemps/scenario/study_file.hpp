#pragma once
// Study files (docs/study.md): JSON text -> a validated study::Study, read as strictly as
// scenario files are. Errors are ScenarioErrors whose message opens "study error at".

#include <filesystem>
#include <string>

#include "swemps/study/study.hpp"

namespace swemps::scenario {

// Reads and validates a study file. The scene and output paths inside it are taken relative
// to the file's folder; the output defaults to <file stem>.csv there. The scene is only
// named here: the study command loads it. Throws ScenarioError (file unreadable, syntax,
// unknown key, bad value).
study::Study load_study(const std::filesystem::path& file);

// The same from text; `base_dir` resolves relative paths, `default_output` is the table's
// path when the text gives none.
study::Study parse_study(const std::string& text, const std::filesystem::path& base_dir,
                         const std::filesystem::path& default_output);

}  // namespace swemps::scenario
