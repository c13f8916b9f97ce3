#pragma once
// Private to the io module: reading a finished result file (a run's netCDF output), for the
// products made from it (flood_products.cpp, ensemble_products.cpp).

#include <netcdf.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "netcdf_layout.hpp"

namespace swemps::io::netcdf {

// Reads what the products need from a result file, read-only.
class ResultReader {
 public:
  explicit ResultReader(const std::filesystem::path& file) : file_(file) {
    const int status = nc_open(file.c_str(), NC_NOWRITE, &ncid_);
    if (status != NC_NOERR) {
      ncid_ = -1;
      throw std::runtime_error("cannot read the result " + quoted(file) + ": " +
                               nc_strerror(status));
    }
  }
  ~ResultReader() {
    if (ncid_ >= 0) nc_close(ncid_);
  }
  ResultReader(const ResultReader&) = delete;
  ResultReader& operator=(const ResultReader&) = delete;

  bool has(const char* name) const {
    int id = -1;
    return nc_inq_varid(ncid_, name, &id) == NC_NOERR;
  }

  int variable(const char* name) const {
    int id = -1;
    if (nc_inq_varid(ncid_, name, &id) != NC_NOERR) {
      throw std::runtime_error("the result " + quoted(file_) + " has no variable " + name +
                               " (is it a swe-mps result?)");
    }
    return id;
  }

  std::size_t length(int varid) const {
    int ndims = 0;
    ok(nc_inq_varndims(ncid_, varid, &ndims), "read the dimensions of a variable");
    std::vector<int> dims(static_cast<std::size_t>(ndims));
    ok(nc_inq_vardimid(ncid_, varid, dims.data()), "read the dimensions of a variable");
    std::size_t n = 1;
    for (const int d : dims) {
      std::size_t len = 0;
      ok(nc_inq_dimlen(ncid_, d, &len), "read a dimension's length");
      n *= len;
    }
    return n;
  }

  // The whole variable as doubles, its fill value as NaN.
  std::vector<double> values(const char* name) const {
    const int id = variable(name);
    std::vector<double> out(length(id));
    ok(nc_get_var_double(ncid_, id, out.data()), std::string("read variable ") + name);
    double fill = std::numeric_limits<double>::quiet_NaN();
    if (nc_get_att_double(ncid_, id, "_FillValue", &fill) == NC_NOERR) {
      for (double& v : out) {
        if (v == fill) v = std::numeric_limits<double>::quiet_NaN();
      }
    }
    return out;
  }

  std::vector<std::string> strings(const char* name) const {
    const int id = variable(name);
    std::vector<char*> raw(length(id));
    ok(nc_get_var_string(ncid_, id, raw.data()), std::string("read variable ") + name);
    std::vector<std::string> out(raw.begin(), raw.end());
    nc_free_string(raw.size(), raw.data());
    return out;
  }

  // A text attribute of a variable (NC_GLOBAL for the file's); empty when absent.
  std::string text(int varid, const char* name) const {
    std::size_t n = 0;
    if (nc_inq_attlen(ncid_, varid, name, &n) != NC_NOERR) return {};
    nc_type type = NC_NAT;
    ok(nc_inq_atttype(ncid_, varid, name, &type), std::string("read attribute ") + name);
    if (type != NC_CHAR) return {};
    std::string value(n, '\0');
    ok(nc_get_att_text(ncid_, varid, name, value.data()), std::string("read attribute ") + name);
    return value;
  }

  // A numeric attribute of a variable (NC_GLOBAL for the file's); NaN when absent.
  double number(int varid, const char* name) const {
    double value = std::numeric_limits<double>::quiet_NaN();
    std::size_t n = 0;
    if (nc_inq_attlen(ncid_, varid, name, &n) != NC_NOERR || n != 1) return value;
    ok(nc_get_att_double(ncid_, varid, name, &value), std::string("read attribute ") + name);
    return value;
  }

  // The grid of the maps: cell centres from x and y, the CRS from the grid mapping.
  Grid grid() const {
    const std::vector<double> x = values("x"), y = values("y");
    if (x.empty() || y.empty()) {
      throw std::runtime_error("the result " + quoted(file_) + " has an empty grid");
    }
    Grid g;
    g.x0 = x.front();
    g.y0 = y.front();
    g.nx = x.size();
    g.ny = y.size();
    // One cell along an axis has no spacing of its own: it takes the other axis's.
    g.dx = g.nx > 1 ? x[1] - x[0] : (g.ny > 1 ? y[1] - y[0] : 1.0);
    g.dy = g.ny > 1 ? y[1] - y[0] : g.dx;
    if (has("crs")) g.crs_wkt = text(variable("crs"), "crs_wkt");
    return g;
  }

 private:
  void ok(int status, const std::string& purpose) const { check(status, purpose, file_); }

  const std::filesystem::path& file_;
  int ncid_ = -1;
};

// "0.3" for 0.3 m: the threshold as a file name part.
inline std::string threshold_text(double threshold_m) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", threshold_m);
  return text;
}

}  // namespace swemps::io::netcdf
