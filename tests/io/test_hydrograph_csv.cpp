// Tests of the hydrograph CSV reader: the accepted forms, and one clear line for each problem.

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "swemps/io/hydrograph_csv.hpp"

using namespace swemps;

namespace {

// A file in the temporary directory holding `text`, removed when the test ends.
class TemporaryFile {
 public:
  TemporaryFile(const std::string& stem, const std::string& text)
      : path_(std::filesystem::temp_directory_path() /
              ("swemps-hydrograph-" + std::to_string(::getpid()) + "-" + stem + ".csv")) {
    std::ofstream(path_, std::ios::binary) << text;
  }
  ~TemporaryFile() { std::filesystem::remove(path_); }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The message of the error reading `text` raises.
std::string error_reading(const std::string& stem, const std::string& text) {
  const TemporaryFile file(stem, text);
  try {
    io::read_hydrograph_csv(file.path());
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  FAIL("no error for " << text);
  return {};
}

}  // namespace

TEST_CASE("hydrograph CSV: comments, blank lines, spaces and Windows line ends",
          "[hydrograph][io]") {
  const TemporaryFile file("good",
                           "# upstream gauge, 2024 event\r\n"
                           "\r\n"
                           "time_s, discharge_m3_s\r\n"
                           "0, 0\r\n"
                           "  # rising limb\r\n"
                           "600 , 12.5\r\n"
                           "\r\n"
                           "1.8e3,+3.25\r\n");
  const auto points = io::read_hydrograph_csv(file.path());
  REQUIRE(points.size() == 3);
  CHECK(points[0] == std::array<double, 2>{0.0, 0.0});
  CHECK(points[1] == std::array<double, 2>{600.0, 12.5});
  CHECK(points[2] == std::array<double, 2>{1800.0, 3.25});
}

TEST_CASE("hydrograph CSV: the header forms accepted", "[hydrograph][io]") {
  for (const std::string header :
       {"time,discharge", "Time,Discharge", "t,Q", "time_s,discharge_m3_s", "t [s],Q [m3/s]",
        "time (s), discharge (m^3/s)", "TIME [S],Q [m3 s-1]"}) {
    const TemporaryFile file("header", header + "\n1,2\n3,4\n");
    INFO(header);
    CHECK(io::read_hydrograph_csv(file.path()) ==
          std::vector<std::array<double, 2>>{{1.0, 2.0}, {3.0, 4.0}});
  }
  // Columns in the other order: still (time, discharge) points.
  const TemporaryFile swapped("swapped", "Q [m3/s],time_s\n2,1\n4,3\n");
  CHECK(io::read_hydrograph_csv(swapped.path()) ==
        std::vector<std::array<double, 2>>{{1.0, 2.0}, {3.0, 4.0}});
}

TEST_CASE("hydrograph CSV: every problem is one line naming the file and the line",
          "[hydrograph][io]") {
  const auto missing = std::filesystem::temp_directory_path() / "swemps-no-such-hydrograph.csv";
  CHECK_THROWS_WITH(io::read_hydrograph_csv(missing),
                    Catch::StartsWith(missing.string() + ": ") && Catch::Contains("cannot open"));

  struct Case {
    std::string text, where, what;
  };
  const std::vector<Case> cases{
      {"", ".csv: ", "no header"},
      {"# only a comment\n\n", ".csv: ", "no header"},
      {"time,discharge\n# nothing else\n", ".csv: ", "no data"},
      {"0,1\n1,2\n", ".csv:1: ", "holds numbers, not a header"},
      {"time,flow\n0,1\n", ".csv:1: ", "column 'flow'"},
      {"time [h],discharge\n0,1\n", ".csv:1: ", "times must be in s, not 'h'"},
      {"time,discharge_l_s\n0,1\n", ".csv:1: ", "discharges must be in m3/s, not 'l_s'"},
      {"time,t\n0,1\n", ".csv:1: ", "same column twice"},
      {"time,discharge,stage\n0,1,2\n", ".csv:1: ", "two columns"},
      {"time,discharge\n0,1\n\n1,2,3\n", ".csv:4: ", "expected 2 columns, found 3"},
      {"time,discharge\n0,1\n1\n", ".csv:3: ", "expected 2 columns, found 1"},
      {"time,discharge\n0,1\n1,abc\n", ".csv:3: ", "discharge 'abc' is not a number"},
      {"time,discharge\n0,1\n1.5x,2\n", ".csv:3: ", "time '1.5x' is not a number"},
      {"time,discharge\n0,1\n1,\n", ".csv:3: ", "discharge '' is not a number"},
      {"time,discharge\n0,nan\n", ".csv:2: ", "not a number"},
      {"time,discharge\n0,inf\n", ".csv:2: ", "not a number"},
      {"time,discharge\n0,1\n# a comment\n5,1\n5,2\n", ".csv:5: ", "not after the previous"},
      {"time,discharge\n0,1\n5,1\n4,2\n", ".csv:4: ", "not after the previous"},
      {"time,discharge\n0,1\n5,-0.5\n", ".csv:3: ", "discharge -0.5 m3/s is negative"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    INFO(c.text);
    const std::string message = error_reading("bad" + std::to_string(k), c.text);
    CHECK_THAT(message, Catch::Contains("-bad" + std::to_string(k) + c.where));
    CHECK_THAT(message, Catch::Contains(c.what));
    CHECK(message.find('\n') == std::string::npos);
  }
}
