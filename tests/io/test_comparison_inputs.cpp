// The reference series a study reads: a CSV table of numbers, read strictly.

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../support/temp_dir.hpp"
#include "swemps/io/comparison_inputs.hpp"

using Catch::Matchers::Contains;
using swemps::io::read_numeric_csv;

TEST_CASE("a numeric table keeps its columns, skips comments and reads empty fields as NaN",
          "[io][table]") {
  const swemps::testing::TempDir dir("numeric-table");
  const auto file = dir.path() / "gauges.csv";
  std::ofstream(file) << "# a grid model's gauges\n"
                         "time_s, a_depth_m ,b_depth_m\r\n"
                         "\n"
                         "0,0.5,\n"
                         "30, 1e-1, 2\n";
  const auto table = read_numeric_csv(file);
  REQUIRE(table.columns == std::vector<std::string>{"time_s", "a_depth_m", "b_depth_m"});
  CHECK(table.column("time_s") == std::vector<double>{0.0, 30.0});
  CHECK(table.column("a_depth_m") == std::vector<double>{0.5, 0.1});
  CHECK(std::isnan(table.column("b_depth_m")[0]));
  CHECK(table.column("b_depth_m")[1] == 2.0);
  CHECK_THROWS_WITH(table.column("c_depth_m"),
                    Contains("no column 'c_depth_m'") && Contains("time_s, a_depth_m, b_depth_m"));
}

TEST_CASE("a numeric table with a wrong row is refused at its line", "[io][table]") {
  const swemps::testing::TempDir dir("numeric-table-bad");
  const auto file = dir.path() / "bad.csv";
  std::ofstream(file) << "time_s,depth\n0,1\n30,1,2\n";
  CHECK_THROWS_WITH(read_numeric_csv(file),
                    Contains("bad.csv:3: 3 fields, where the header names 2"));
  std::ofstream(file) << "time_s,depth\n0,one\n";
  CHECK_THROWS_WITH(read_numeric_csv(file),
                    Contains("bad.csv:2: 'one' in column depth is not a number"));
  std::ofstream(file) << "# nothing but a comment\n";
  CHECK_THROWS_WITH(read_numeric_csv(file), Contains("no header"));
  CHECK_THROWS_WITH(read_numeric_csv(dir.path() / "none.csv"), Contains("cannot be read"));
}
