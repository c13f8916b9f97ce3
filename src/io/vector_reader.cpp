#include "swemps/io/vector_reader.hpp"

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <memory>
#include <stdexcept>

#include "swemps/io/gdal_messages.hpp"

namespace swemps::io {

namespace {

class VectorError {
 public:
  explicit VectorError(const VectorRequest& request)
      : prefix_(request.purpose + " '" + request.path.string() + "': ") {}
  [[noreturn]] void operator()(const std::string& problem) const {
    throw std::runtime_error(prefix_ + problem);
  }

 private:
  std::string prefix_;
};

// A CRS from the scene's words; `what` names it in messages.
OGRSpatialReference parse_crs(const std::string& text, const std::string& what,
                              const VectorError& fail) {
  OGRSpatialReference crs;
  crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (crs.SetFromUserInput(text.c_str(),
                           OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS_get()) !=
      OGRERR_NONE) {
    fail(what + " is not a CRS GDAL understands" + gdal_detail());
  }
  return crs;
}

std::string crs_name(const OGRSpatialReference& crs) {
  const char* name = crs.GetName();
  const char* authority = crs.GetAuthorityName(nullptr);
  const char* code = crs.GetAuthorityCode(nullptr);
  std::string text = name ? name : "unnamed";
  if (authority && code) text += std::string(" (") + authority + ":" + code + ")";
  return text;
}

terrain::Ring ring_of(const OGRLinearRing& ring) {
  terrain::Ring out;
  out.reserve(static_cast<std::size_t>(ring.getNumPoints()));
  for (int k = 0; k < ring.getNumPoints(); ++k) {
    const std::array<double, 2> p{ring.getX(k), ring.getY(k)};
    if (out.empty() || p != out.back()) out.push_back(p);
  }
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

// Appends the polygons of `geometry`; returns false when it holds none.
bool collect(const OGRGeometry& geometry, PolygonLayer& layer) {
  const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
  if (type == wkbPolygon) {
    const auto& polygon = *geometry.toPolygon();
    const OGRLinearRing* outer = polygon.getExteriorRing();
    if (!outer) return true;
    terrain::Footprint f{ring_of(*outer), {}};
    if (f.outer.size() < 3) {
      ++layer.degenerate;
      return true;
    }
    for (int h = 0; h < polygon.getNumInteriorRings(); ++h) {
      terrain::Ring hole = ring_of(*polygon.getInteriorRing(h));
      if (hole.size() >= 3) f.holes.push_back(std::move(hole));
    }
    layer.polygons.push_back(std::move(f));
    return true;
  }
  if (type == wkbCurvePolygon) {
    std::unique_ptr<OGRGeometry> linear(geometry.getLinearGeometry());
    return linear && collect(*linear, layer);
  }
  if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
    std::unique_ptr<OGRGeometry> linear(geometry.hasCurveGeometry() ? geometry.getLinearGeometry()
                                                                    : geometry.clone());
    bool any = false;
    for (const OGRGeometry* part : *linear->toGeometryCollection()) {
      if (part) any = collect(*part, layer) || any;
    }
    return any;
  }
  return false;
}

}  // namespace

PolygonLayer read_polygons(const VectorRequest& request) {
  register_gdal_drivers();
  const QuietGdalErrors quiet;
  const VectorError fail(request);
  GDALDatasetUniquePtr dataset(GDALDataset::Open(
      request.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR));
  if (!dataset) {
    std::error_code ec;
    if (!std::filesystem::exists(request.path, ec)) fail("file not found");
    fail("is not a vector file GDAL can read" + gdal_detail());
  }
  if (dataset->GetLayerCount() == 0) fail("holds no vector layer");
  OGRLayer* source =
      request.layer.empty() ? dataset->GetLayer(0) : dataset->GetLayerByName(request.layer.c_str());
  if (!source) {
    std::string names;
    for (int k = 0; k < dataset->GetLayerCount(); ++k) {
      names += (k ? ", '" : "'") + std::string(dataset->GetLayer(k)->GetName()) + "'";
    }
    fail("has no layer '" + request.layer + "' (it has " + names + ")");
  }

  PolygonLayer layer;
  layer.layer = source->GetName();
  // Where the file's coordinates are, and where they must go.
  const bool as_scene = request.file_crs == "scene";
  const bool scene_has_crs = !request.scene_crs.empty();
  OGRSpatialReference scene;
  if (scene_has_crs) scene = parse_crs(request.scene_crs, request.scene_crs_name, fail);
  std::unique_ptr<OGRSpatialReference> file;
  if (as_scene) {
    // as they are
  } else if (const OGRSpatialReference* own = source->GetSpatialRef(); own && !own->IsEmpty()) {
    file = std::make_unique<OGRSpatialReference>(*own);
  } else if (!request.file_crs.empty()) {
    file = std::make_unique<OGRSpatialReference>(parse_crs(
        request.file_crs, request.file_crs_setting + " = \"" + request.file_crs + "\"", fail));
  }
  if (file) file->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> transform;
  if (scene_has_crs && !file && !as_scene) {
    fail("has no CRS, so it cannot be placed in " + request.scene_crs_name +
         "; give the file a "
         "CRS (a .prj beside a Shapefile), or set " +
         request.file_crs_setting + " to the CRS its coordinates are in (\"scene\": the scene's)");
  }
  if (!scene_has_crs && file) {
    fail("is in " + crs_name(*file) +
         " in a scene whose rasters have no CRS; give the scene's "
         "rasters a CRS, or set " +
         request.file_crs_setting + " to \"scene\" if its coordinates are the scene's metres");
  }
  if (scene_has_crs && file && !file->IsSame(&scene)) {
    if (!request.reproject) {
      fail("is in " + crs_name(*file) + ", not in " + request.scene_crs_name + " (" +
           crs_name(scene) + "); set " + request.reproject_setting +
           " to true to transform it, or " + request.file_crs_setting +
           " to \"scene\" if its coordinates are the scene's already");
    }
    transform.reset(OGRCreateCoordinateTransformation(file.get(), &scene));
    if (!transform) {
      fail("cannot be transformed from " + crs_name(*file) + " to " + crs_name(scene) +
           gdal_detail());
    }
  }

  source->ResetReading();
  for (auto& feature : *source) {
    ++layer.features;
    OGRGeometry* geometry = feature->GetGeometryRef();
    if (!geometry || geometry->IsEmpty()) {
      ++layer.not_polygons;
      continue;
    }
    if (transform && geometry->transform(transform.get()) != OGRERR_NONE) {
      fail("feature " + std::to_string(feature->GetFID()) + " cannot be transformed to " +
           crs_name(scene) + gdal_detail());
    }
    if (!collect(*geometry, layer)) ++layer.not_polygons;
  }
  if (layer.polygons.empty()) {
    fail("layer '" + layer.layer + "' holds no polygon (" + std::to_string(layer.features) +
         " features)");
  }
  return layer;
}

}  // namespace swemps::io
