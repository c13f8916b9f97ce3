#pragma once
// A fresh folder per test case, removed afterwards, so parallel test runs never collide.

#include <chrono>
#include <filesystem>
#include <random>
#include <string>
#include <system_error>

namespace swemps::testing {

class TempDir {
 public:
  // `purpose` names the folder ("netcdf", "raster" ...) so a leftover one says who made it.
  explicit TempDir(const std::string& purpose = "test") {
    std::random_device rd;
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    dir_ = std::filesystem::temp_directory_path() /
           ("swemps-" + purpose + "-test-" + std::to_string(stamp) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace swemps::testing
