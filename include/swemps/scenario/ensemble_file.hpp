#pragma once
// Ensemble files (docs/ensembles.md): JSON text -> a validated ensemble::Ensemble, read as
// strictly as scenario files are, and each member's scene made from the base scene. Errors
// are ScenarioErrors whose message opens "ensemble error at".

#include <filesystem>
#include <string>

#include "swemps/ensemble/ensemble.hpp"

namespace swemps::scenario {

// Reads and validates an ensemble file. The scene and folder paths inside it are taken
// relative to the file's folder; the folder defaults to the file's name without its extension,
// beside it. Every knob's pointer is checked against the base scene: its parent must be there
// (an object, or an array whose element it replaces). Throws ScenarioError.
ensemble::Ensemble load_ensemble(const std::filesystem::path& file);

// The same from text; `file` is the ensemble file's path (absolute), which relative paths are
// resolved against and which names the default folder.
ensemble::Ensemble parse_ensemble(const std::string& text, const std::filesystem::path& file);

// The scene of one member, as JSON text to be kept as <member folder>/scenario.json: the base
// scene with each knob's value put at its pointer, every file the scene names (the bed and
// roughness rasters, the depth rasters, the hydrograph tables) made relative to
// `member_folder` (a knob's file name is taken relative to the base scene's folder, as the
// base scene's own are), and the output path set to result.nc. Throws ScenarioError at the
// knob ("ensemble error at /vary/K") when a value cannot be put where its pointer says.
std::string member_scene(const ensemble::Ensemble& ensemble, const ensemble::Member& member,
                         const std::filesystem::path& member_folder);

// The file name a member's result is written under, in its folder.
inline constexpr const char* kMemberResult = "result.nc";

}  // namespace swemps::scenario
