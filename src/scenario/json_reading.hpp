#pragma once
// Reading JSON documents strictly, for the files the scenario module reads (scenes and study
// files): unknown and repeated keys are errors, types are strict, and every problem becomes a
// ScenarioError naming the JSON path, what was found and what was expected, with a "did you
// mean" hint for near misses. Private to the module: nothing outside src/scenario sees JSON.

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario::json_reading {

using json = nlohmann::json;
using Names = std::vector<std::string_view>;

extern const std::string kMissing;  // the "found" of a required key that is absent
extern const std::string kMetres;   // units named in what a number should be
extern const std::string kSeconds;

// ---------------------------------------------------------------------------------------------
// Text for messages

std::string fmt(double v);  // 12 significant digits
// A JSON string literal; invalid UTF-8 is replaced, since it goes into a message.
std::string literal(std::string_view s);
// What a value is, in words, for the "found" part of an error.
std::string describe(const json& v);
// JSON-pointer paths (RFC 6901 escapes "~" and "/" inside keys).
std::string member_path(const std::string& parent, std::string_view key);
std::string element_path(const std::string& parent, std::size_t index);
std::string join(const Names& names, bool quote);
// " (did you mean "x"?)" when one of `choices` is close to `word`, else "".
std::string did_you_mean(std::string_view word, const Names& choices);

// ---------------------------------------------------------------------------------------------
// Reading values

// A JSON object with a fixed set of allowed keys: an unknown key is an error, so a typo never
// silently falls back to a default.
class Object {
 public:
  Object(const json& value, std::string path, Names keys, const std::string& expected)
      : value_(value), path_(std::move(path)), keys_(std::move(keys)) {
    if (!value_.is_object()) throw ScenarioError(path_, describe(value_), expected);
    for (auto it = value_.begin(); it != value_.end(); ++it) {
      if (std::find(keys_.begin(), keys_.end(), it.key()) == keys_.end()) {
        throw ScenarioError(
            this->path(it.key()), "an unknown key " + literal(it.key()),
            "one of the keys " + join(keys_, false) + did_you_mean(it.key(), keys_));
      }
    }
  }

  const json* find(std::string_view key) const {
    const auto it = value_.find(std::string(key));
    return it == value_.end() ? nullptr : &*it;
  }
  std::string path(std::string_view key) const { return member_path(path_, key); }
  const std::string& path() const { return path_; }

 private:
  const json& value_;
  std::string path_;
  Names keys_;
};

// The scene as it is run: a copy of the document into which every default a reading falls
// back on is written at its path, as the reading takes it. While one is alive, the readers
// below record into it (one per thread; none: nothing is recorded). A default at a path the
// document cannot hold (under a value that is not an object) is left out.
class DefaultsRecord {
 public:
  explicit DefaultsRecord(const json& document);
  ~DefaultsRecord();
  DefaultsRecord(const DefaultsRecord&) = delete;
  DefaultsRecord& operator=(const DefaultsRecord&) = delete;
  const json& document() const { return document_; }
  // Records `value` at the JSON pointer `path` in the current record, if there is one.
  static void note(const std::string& path, const json& value);
  // Takes back what was recorded at `path`: a default of a key that the rest of the scene
  // rules out (a knob of the scheme not chosen), which read again would be refused.
  static void drop(const std::string& path);

 private:
  json document_;
  DefaultsRecord* outer_;
};

// {}, for optional sections that are absent: read as all defaults.
const json& empty_object();

double finite_number(const json& v, const std::string& path, const std::string& expected);
// o[key] as a finite number; a missing key gives `fallback`, or an error when there is none.
double number(const Object& o, std::string_view key, const std::string& expected,
              std::optional<double> fallback = std::nullopt);
double positive(const Object& o, std::string_view key, const std::string& unit,
                std::optional<double> fallback = std::nullopt);
// An integer within [low, high] written as a JSON number, such as 1000 or 1e3.
int whole_number(const Object& o, std::string_view key, int low, int high,
                 const std::string& meaning, int fallback);
double non_negative(const Object& o, std::string_view key, const std::string& unit,
                    double fallback);
// A number within [low, high], each end excluded when it is open.
double in_range(const Object& o, std::string_view key, double low, bool open_low, double high,
                bool open_high, const std::string& meaning, double fallback);
// A number within [low, high] (the lower end excluded when `open_low`).
double bounded(const Object& o, std::string_view key, double low, bool open_low, double high,
               const std::string& meaning, double fallback);
std::optional<std::string> optional_string(const Object& o, std::string_view key,
                                           const std::string& expected);
// One of a fixed set of words; a near miss gets a suggestion.
std::string_view choice(const Object& o, std::string_view key, const Names& choices,
                        std::string_view fallback);
// The same for a value that is not under a key (an array element).
std::string_view word(const json& v, const std::string& path, const Names& choices);
bool optional_bool(const Object& o, std::string_view key, bool fallback);

// o[key], a non-empty string naming a file or folder, taken relative to `base_dir` when it is
// relative; absolute and normalised. `folder` names base_dir in messages ("the study file's
// folder"); `what` says what the path is for.
std::filesystem::path path_value(const Object& o, std::string_view key, const std::string& what,
                                 const std::filesystem::path& base_dir, const std::string& folder);

// ---------------------------------------------------------------------------------------------
// Documents

// The text as JSON; syntax errors and repeated keys are ScenarioErrors at the root ("") or at
// the repeated key.
json parse_json(const std::string& text);

// The whole file as text. Throws ScenarioError at the root, "found" saying why the file
// cannot be read and "expected" being `expected` ("a readable scenario JSON file").
std::string read_text_file(const std::filesystem::path& file, const std::string& expected);

}  // namespace swemps::scenario::json_reading
