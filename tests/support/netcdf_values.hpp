#pragma once
// Reading back what a run wrote: every value of a netCDF variable of any shape, as doubles.

#include <netcdf.h>

#include <catch2/catch.hpp>
#include <cstddef>
#include <vector>

namespace swemps::testing {

// The variable `name` of the open file `ncid`, whole (the last dimension fastest).
inline std::vector<double> whole_variable(int ncid, const char* name) {
  int var = -1, rank = 0;
  REQUIRE(nc_inq_varid(ncid, name, &var) == NC_NOERR);
  REQUIRE(nc_inq_varndims(ncid, var, &rank) == NC_NOERR);
  std::vector<int> dims(static_cast<std::size_t>(rank));
  REQUIRE(nc_inq_vardimid(ncid, var, dims.data()) == NC_NOERR);
  std::size_t total = 1;
  for (const int d : dims) {
    std::size_t n = 0;
    REQUIRE(nc_inq_dimlen(ncid, d, &n) == NC_NOERR);
    total *= n;
  }
  std::vector<double> values(total);
  if (total > 0) REQUIRE(nc_get_var_double(ncid, var, values.data()) == NC_NOERR);
  return values;
}

}  // namespace swemps::testing
