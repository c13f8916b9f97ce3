#!/usr/bin/env bash
# Installs the Debian packages swe-mps needs to build, test and plot, and only those that
# are missing. Run as root (or with sudo) on Debian bookworm.
set -euo pipefail

packages=(
  cmake make g++                  # toolchain (OpenMP ships with g++)
  libeigen3-dev                   # linear algebra
  libgdal-dev gdal-bin            # raster input; gdalinfo to inspect outputs
  libnetcdf-dev netcdf-bin        # netCDF output; ncdump to inspect it
  nlohmann-json3-dev              # scenario files
  libspdlog-dev                   # logging
  catch2                          # unit tests (v2)
  clang libclang-rt-dev           # the scenario-parser fuzzer (libFuzzer); see tests/fuzz/
  python3-matplotlib python3-netcdf4 python3-numpy   # plots in docs/
  python3-xarray python3-gdal      # tests open the flood maps with xarray; DEM conversion tool
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
