#pragma once
// Polygons in: building footprints and other obstacles from any vector file GDAL/OGR can open
// (GeoJSON, Shapefile, GeoPackage, ...), in the scene's CRS. Unlike rasters, which are warped
// to the scene's CRS as a matter of course, a vector file in another CRS is moved only when
// the scene asks (`reproject`): a footprint a few metres off lands on the street, and a file in
// the wrong CRS is more often a mistake than an intent.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "swemps/terrain/footprints.hpp"

namespace swemps::io {

struct VectorRequest {
  std::filesystem::path path;
  std::string layer;                    // empty: the file's first layer
  std::string purpose = "vector file";  // in messages ("building file")
  // The scene's CRS (anything OGRSpatialReference::SetFromUserInput accepts without reading
  // files, or WKT); empty: local metres, no CRS. `scene_crs_name` says where it comes from.
  std::string scene_crs;
  std::string scene_crs_name = "the scene's CRS";
  // The file's CRS when it declares none (a Shapefile without its .prj); empty: none given.
  // "scene": the coordinates are in the scene's CRS (or its local metres) whatever the file
  // declares: a GeoJSON file without a "crs" member is longitude/latitude to GDAL, as RFC 7946
  // has it, even when a tool wrote projected coordinates into it.
  std::string file_crs;
  std::string file_crs_setting = "crs";         // the scene key that sets file_crs, in messages
  bool reproject = false;                       // transform a file in another CRS to the scene's
  std::string reproject_setting = "reproject";  // the scene key, in messages
};

struct PolygonLayer {
  std::string layer;  // the layer read
  std::vector<terrain::Footprint> polygons;
  std::size_t features = 0;      // features in the layer
  std::size_t not_polygons = 0;  // features without a polygon (points, lines, none): left out
  std::size_t degenerate = 0;    // polygons with fewer than 3 distinct vertices: left out
};

// Reads every polygon of the layer (Polygon, MultiPolygon, curved polygons as line segments,
// and the polygons in a geometry collection), each part a footprint with its holes; repeated
// vertices are dropped and rings are left open. Heights (Z) are ignored.
//  - a file in the scene's CRS, or without a CRS in a scene without one, is read as it is;
//  - a file in another CRS is an error unless request.reproject, which transforms it;
//  - a file without a CRS in a scene with one is an error unless request.file_crs names it;
//  - request.file_crs "scene" takes the coordinates as they are;
//  - a layer without one polygon is an error.
// Throws std::runtime_error, one line naming the purpose, the file and the problem.
PolygonLayer read_polygons(const VectorRequest& request);

}  // namespace swemps::io
