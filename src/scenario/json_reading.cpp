#include "json_reading.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <set>
#include <sstream>

namespace swemps::scenario::json_reading {

const std::string kMissing = "nothing (key missing)";
const std::string kMetres = "metres";
const std::string kSeconds = "seconds";

// ---------------------------------------------------------------------------------------------
// Text helpers

std::string fmt(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

// A JSON string literal; invalid UTF-8 is replaced rather than thrown on, since it goes into
// an error message that must always be produced.
std::string literal(std::string_view s) {
  return json(std::string(s)).dump(-1, ' ', false, json::error_handler_t::replace);
}

// What a value is, in words, for the "found" part of an error.
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "a string " + literal(s);
    }
    case json::value_t::array:
      if (v.empty()) return "an empty array";
      return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
    case json::value_t::object: return v.empty() ? "an empty object" : "an object";
    default: return v.dump();
  }
}

// JSON-pointer paths (RFC 6901 escapes "~" and "/" inside keys).
std::string member_path(const std::string& parent, std::string_view key) {
  std::string out = parent + "/";
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string element_path(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

std::string join(const Names& names, bool quote) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += ", ";
    out += quote ? literal(names[i]) : std::string(names[i]);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Suggestions for misspelt keys and values

namespace {

std::string lowered(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Optimal-string-alignment distance: insertions, deletions, substitutions and swaps of
// neighbours, so the common typing slip "dpeth" is one edit from "depth". Case is ignored.
std::size_t edit_distance(std::string_view a_in, std::string_view b_in) {
  const std::string a = lowered(a_in), b = lowered(b_in);
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

}  // namespace

// " (did you mean "x"?)" when one of `choices` is close to `word`, else "".
std::string did_you_mean(std::string_view word, const Names& choices) {
  std::optional<std::string_view> best;
  std::size_t best_distance = 0;
  for (std::string_view c : choices) {
    const std::size_t d = edit_distance(word, c);
    if (!best || d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  // Short words tolerate two edits, longer ones a third of their length.
  const std::size_t tolerance = std::max<std::size_t>(2, word.size() / 3);
  if (!best || best_distance > tolerance) return "";
  return " (did you mean " + literal(*best) + "?)";
}

// ---------------------------------------------------------------------------------------------
// Reading values

const json& empty_object() {
  static const json empty = json::object();
  return empty;
}

double finite_number(const json& v, const std::string& path, const std::string& expected) {
  if (!v.is_number()) throw ScenarioError(path, describe(v), expected);
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw ScenarioError(path, describe(v), expected);
  return x;
}

namespace {
// The record the readers write into on this thread; null: none.
thread_local DefaultsRecord* current_record = nullptr;
}  // namespace

DefaultsRecord::DefaultsRecord(const json& document) : document_(document), outer_(current_record) {
  current_record = this;
}

DefaultsRecord::~DefaultsRecord() { current_record = outer_; }

void DefaultsRecord::note(const std::string& path, const json& value) {
  if (current_record == nullptr) return;
  try {
    json& at = current_record->document_[json::json_pointer(path)];
    if (at.is_null()) at = value;
  } catch (const json::exception&) {
    // A path through a value that is not an object (a bed given as a file name, say).
  }
}

void DefaultsRecord::drop(const std::string& path) {
  if (current_record == nullptr) return;
  try {
    const json::json_pointer pointer(path);
    json& parent = current_record->document_[pointer.parent_pointer()];
    if (parent.is_object()) parent.erase(pointer.back());
  } catch (const json::exception&) {
    // Nothing was recorded there.
  }
}

// o[key] as a finite number; a missing key gives `fallback`, or an error when there is none.
double number(const Object& o, std::string_view key, const std::string& expected,
              std::optional<double> fallback) {
  const json* v = o.find(key);
  if (v == nullptr) {
    if (fallback) {
      DefaultsRecord::note(o.path(key), *fallback);
      return *fallback;
    }
    throw ScenarioError(o.path(key), kMissing, expected);
  }
  return finite_number(*v, o.path(key), expected);
}

int whole_number(const Object& o, std::string_view key, int low, int high,
                 const std::string& meaning, int fallback) {
  const std::string expected = "a whole number from " + std::to_string(low) + " to " +
                               std::to_string(high) + " (" + meaning + ")";
  const double x = number(o, key, expected, fallback);
  if (x != std::floor(x) || x < low || x > high) {
    throw ScenarioError(o.path(key), describe(*o.find(key)), expected);
  }
  return static_cast<int>(x);
}

double positive(const Object& o, std::string_view key, const std::string& unit,
                std::optional<double> fallback) {
  const std::string expected = "a number > 0 (" + unit + ")";
  const double x = number(o, key, expected, fallback);
  if (!(x > 0.0)) throw ScenarioError(o.path(key), describe(*o.find(key)), expected);
  return x;
}

// A number within [low, high], each end excluded when it is open.
double in_range(const Object& o, std::string_view key, double low, bool open_low, double high,
                bool open_high, const std::string& meaning, double fallback) {
  const std::string expected = "a number in " + std::string(open_low ? "(" : "[") + fmt(low) +
                               ", " + fmt(high) + (open_high ? ")" : "]") + " (" + meaning + ")";
  const double x = number(o, key, expected, fallback);
  const bool above_low = open_low ? x > low : x >= low;
  const bool below_high = open_high ? x < high : x <= high;
  if (!above_low || !below_high) {
    throw ScenarioError(o.path(key), describe(*o.find(key)), expected);
  }
  return x;
}

// A number within [low, high] (the lower end excluded when `open_low`).
double bounded(const Object& o, std::string_view key, double low, bool open_low, double high,
               const std::string& meaning, double fallback) {
  return in_range(o, key, low, open_low, high, false, meaning, fallback);
}

std::optional<std::string> optional_string(const Object& o, std::string_view key,
                                           const std::string& expected) {
  const json* v = o.find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_string()) throw ScenarioError(o.path(key), describe(*v), expected);
  return v->get<std::string>();
}

// One of a fixed set of words; a near miss gets a suggestion.
std::string_view word(const json& v, const std::string& path, const Names& choices) {
  const std::string expected = "one of " + join(choices, true);
  if (!v.is_string()) throw ScenarioError(path, describe(v), expected);
  const auto& given = v.get_ref<const std::string&>();
  for (std::string_view c : choices) {
    if (c == given) return c;
  }
  throw ScenarioError(path, describe(v), expected + did_you_mean(given, choices));
}

std::string_view choice(const Object& o, std::string_view key, const Names& choices,
                        std::string_view fallback) {
  const json* v = o.find(key);
  if (v == nullptr) {
    DefaultsRecord::note(o.path(key), std::string(fallback));
    return fallback;
  }
  return word(*v, o.path(key), choices);
}

bool optional_bool(const Object& o, std::string_view key, bool fallback) {
  const json* v = o.find(key);
  if (v == nullptr) {
    DefaultsRecord::note(o.path(key), fallback);
    return fallback;
  }
  if (!v->is_boolean()) throw ScenarioError(o.path(key), describe(*v), "true or false");
  return v->get<bool>();
}

double non_negative(const Object& o, std::string_view key, const std::string& unit,
                    double fallback) {
  const std::string expected = "a number >= 0 (" + unit + ")";
  const double x = number(o, key, expected, fallback);
  if (!(x >= 0.0)) throw ScenarioError(o.path(key), describe(*o.find(key)), expected);
  return x;
}

// ---------------------------------------------------------------------------------------------
// Parsing the text

namespace {

// Follows the parser through the document so that a key given twice in one object - which
// the JSON library would resolve silently by keeping the last - is reported with its path.
class DuplicateKeyGuard {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    using Event = json::parse_event_t;
    switch (event) {
      case Event::key: on_key(parsed.get<std::string>()); break;
      case Event::object_start:
      case Event::array_start: {
        std::string path = frames_.empty() ? std::string() : next_child();
        // Each level keeps its path, so memory grows with the square of the depth; no
        // scenario needs more than a handful of levels.
        if (frames_.size() >= kMaxNesting) {
          throw ScenarioError(
              path, "containers nested more than " + std::to_string(kMaxNesting) + " levels deep",
              "a scenario nested at most " + std::to_string(kMaxNesting) + " levels deep");
        }
        frames_.push_back(Frame{event == Event::array_start, std::move(path), {}, {}, 0});
        break;
      }
      case Event::object_end:
      case Event::array_end: frames_.pop_back(); break;
      case Event::value:
        if (!frames_.empty()) next_child();  // counts array elements
        break;
    }
    return true;  // keep everything
  }

 private:
  static constexpr std::size_t kMaxNesting = 64;

  struct Frame {
    bool array;
    std::string path;
    std::set<std::string> keys;
    std::string current;  // path of the member being read, in an object
    std::size_t next_index;
  };

  void on_key(const std::string& key) {
    Frame& f = frames_.back();
    f.current = member_path(f.path, key);
    if (!f.keys.insert(key).second) {
      throw ScenarioError(f.current, "the key " + literal(key) + " a second time",
                          "each key at most once in an object");
    }
  }

  // The path of the value that starts now inside the innermost container.
  std::string next_child() {
    Frame& f = frames_.back();
    return f.array ? element_path(f.path, f.next_index++) : f.current;
  }

  std::vector<Frame> frames_;
};

// "line L, column C" of a byte offset, counted as the JSON library counts them.
std::string line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(byte, text.size());
  std::size_t line = 1, column = 0;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The library's message without its "[json.exception.parse_error.N] parse error at ...: "
// prefix, which repeats what line_and_column already says.
std::string bare_parse_message(const std::string& what) {
  std::string msg = what;
  if (const auto bracket = msg.find("] ");
      !msg.empty() && msg[0] == '[' && bracket != std::string::npos) {
    msg.erase(0, bracket + 2);
  }
  if (msg.rfind("parse error", 0) == 0) {
    if (const auto colon = msg.find(": "); colon != std::string::npos) msg.erase(0, colon + 2);
  }
  return msg;
}

}  // namespace

json parse_json(const std::string& text) {
  DuplicateKeyGuard guard;
  try {
    return json::parse(text, std::ref(guard));
  } catch (const json::parse_error& e) {
    throw ScenarioError(
        "",
        "invalid JSON at " + line_and_column(text, e.byte) + ": " + bare_parse_message(e.what()),
        "valid JSON");
  } catch (const json::exception& e) {
    // A number literal beyond double range ends up here, without a position.
    throw ScenarioError("", "invalid JSON: " + bare_parse_message(e.what()), "valid JSON");
  }
}

std::filesystem::path path_value(const Object& o, std::string_view key, const std::string& what,
                                 const std::filesystem::path& base_dir, const std::string& folder) {
  const std::string expected = "a path to " + what + " (relative to " + folder + ")";
  const json* v = o.find(key);
  if (v == nullptr) throw ScenarioError(o.path(key), kMissing, expected);
  if (!v->is_string() || v->get_ref<const std::string&>().empty()) {
    throw ScenarioError(o.path(key), describe(*v), expected);
  }
  std::filesystem::path p(v->get<std::string>());
  if (p.is_relative()) p = base_dir / p;
  return std::filesystem::absolute(p).lexically_normal();
}

std::string read_text_file(const std::filesystem::path& file, const std::string& expected) {
  const std::string cannot = "cannot read file '" + file.string() + "': ";
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    throw ScenarioError("", cannot + "it is a folder", expected);
  }
  errno = 0;  // so that a failure without a system reason is not blamed on an old one
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw ScenarioError("", cannot + (err != 0 ? std::strerror(err) : "cannot open it"), expected);
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw ScenarioError("", cannot + "read failed", expected);
  return buffer.str();
}

}  // namespace swemps::scenario::json_reading
