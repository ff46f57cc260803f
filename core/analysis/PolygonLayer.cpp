#include "PolygonLayer.h"

#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

void PolygonGeometryDeleter::operator()(void* geometry) const {
    OGR_G_DestroyGeometry(static_cast<OGRGeometryH>(geometry));
}

namespace {

std::string gdalMessage(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return message != nullptr && *message != '\0' ? message : fallback;
}

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(static_cast<GDALDatasetH>(dataset)); }
};
using DatasetHandle = std::unique_ptr<void, DatasetCloser>;

struct SpatialReferenceDeleter {
    void operator()(void* reference) const {
        OSRDestroySpatialReference(static_cast<OGRSpatialReferenceH>(reference));
    }
};
using SpatialReferenceHandle = std::unique_ptr<void, SpatialReferenceDeleter>;

bool numericField(OGRFieldType type) {
    return type == OFTReal || type == OFTInteger || type == OFTInteger64;
}

bool isPolygon(OGRGeometryH geometry) {
    const OGRwkbGeometryType type = OGR_GT_Flatten(OGR_G_GetGeometryType(geometry));
    return type == wkbPolygon || type == wkbMultiPolygon;
}

// The index of the value field (-1 without one), or the error naming the data set.
Result<int> valueField(const PolygonLayerRequest& request, OGRLayerH layer) {
    if (request.valueAttribute.empty())
        return -1;
    OGRFeatureDefnH definition = OGR_L_GetLayerDefn(layer);
    const int field = OGR_FD_GetFieldIndex(definition, request.valueAttribute.c_str());
    if (field < 0)
        return Error{request.path + ": no " + request.valueRole + " attribute '" +
                     request.valueAttribute + "'"};
    if (!numericField(OGR_Fld_GetType(OGR_FD_GetFieldDefn(definition, field))))
        return Error{request.path + ": the " + request.valueRole + " attribute '" +
                     request.valueAttribute + "' is not numeric"};
    return field;
}

// One feature's polygon in the grid's CRS, or the reason it is refused.
Result<PolygonFeature> polygonOf(const PolygonLayerRequest& request, OGRFeatureH feature, int field,
                                 OGRSpatialReferenceH target) {
    const std::string name = request.path + ": feature " + std::to_string(OGR_F_GetFID(feature));
    PolygonFeature out;
    if (field >= 0) {
        out.value = OGR_F_GetFieldAsDouble(feature, field);
        if (!OGR_F_IsFieldSetAndNotNull(feature, field) || !(out.value > 0.0) ||
            !std::isfinite(out.value))
            return Error{name + ": the " + request.valueRole + " '" + request.valueAttribute +
                         "' must be a positive number"};
    }
    OGRGeometryH geometry = OGR_F_GetGeometryRef(feature);
    if (geometry == nullptr || OGR_G_IsEmpty(geometry))
        return Error{name + ": no geometry"};
    if (!isPolygon(geometry))
        return Error{name + ": " + request.role + " must be a polygon"};
    out.geometry.reset(OGR_G_Clone(geometry));
    if (OGR_G_GetSpatialReference(geometry) != nullptr &&
        OGR_G_TransformTo(static_cast<OGRGeometryH>(out.geometry.get()), target) != OGRERR_NONE)
        return Error{name + ": cannot reproject the polygon to the DEM's CRS"};
    return out;
}

}  // namespace

Result<std::vector<PolygonFeature>> readPolygons(const PolygonLayerRequest& request,
                                                 const std::string& gridWkt) {
    GdalDatasetPool::registerDrivers();  // a process may reach here before any other GDAL use
    CPLErrorReset();
    DatasetHandle dataset(GDALOpenEx(request.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                     nullptr, nullptr, nullptr));
    if (!dataset)
        return Error{request.path + ": " + gdalMessage("cannot open the vector data set")};
    auto* handle = static_cast<GDALDatasetH>(dataset.get());
    OGRLayerH layer = request.layer.empty()
                          ? GDALDatasetGetLayer(handle, 0)
                          : GDALDatasetGetLayerByName(handle, request.layer.c_str());
    if (layer == nullptr)
        return Error{request.path + ": no layer '" + request.layer + "'"};
    auto field = valueField(request, layer);
    if (!field)
        return field.error();
    SpatialReferenceHandle target(OSRNewSpatialReference(gridWkt.c_str()));
    OSRSetAxisMappingStrategy(static_cast<OGRSpatialReferenceH>(target.get()),
                              OAMS_TRADITIONAL_GIS_ORDER);
    std::vector<PolygonFeature> polygons;
    OGR_L_ResetReading(layer);
    for (OGRFeatureH feature; (feature = OGR_L_GetNextFeature(layer)) != nullptr;) {
        auto polygon =
            polygonOf(request, feature, *field, static_cast<OGRSpatialReferenceH>(target.get()));
        OGR_F_Destroy(feature);
        if (!polygon)
            return polygon.error();
        polygons.push_back(std::move(*polygon));
    }
    return polygons;
}

Result<std::vector<float>> rasterizePolygons(const std::vector<PolygonFeature>& polygons,
                                             const GridGeometry& g, const std::string& gridWkt,
                                             const std::string& path) {
    std::vector<float> burnt(std::size_t(g.width) * std::size_t(g.height), 0.0f);
    if (polygons.empty())
        return burnt;
    DatasetHandle memory(
        GDALCreate(GDALGetDriverByName("MEM"), "", g.width, g.height, 1, GDT_Float32, nullptr));
    if (!memory)
        return Error{path + ": " + gdalMessage("cannot create the raster for the polygons")};
    auto* handle = static_cast<GDALDatasetH>(memory.get());
    double gt[6];
    g.geoTransform(gt);
    GDALSetGeoTransform(handle, gt);
    GDALSetProjection(handle, gridWkt.c_str());
    std::vector<OGRGeometryH> geometries;
    std::vector<double> values;
    for (const PolygonFeature& p : polygons) {
        geometries.push_back(static_cast<OGRGeometryH>(p.geometry.get()));
        values.push_back(p.value);
    }
    int band = 1;
    if (GDALRasterizeGeometries(handle, 1, &band, int(geometries.size()), geometries.data(),
                                nullptr, nullptr, values.data(), nullptr, nullptr,
                                nullptr) != CE_None)
        return Error{path + ": " + gdalMessage("cannot rasterize the polygons")};
    if (GDALRasterIO(GDALGetRasterBand(handle, 1), GF_Read, 0, 0, g.width, g.height, burnt.data(),
                     g.width, g.height, GDT_Float32, 0, 0) != CE_None)
        return Error{path + ": " + gdalMessage("cannot read the rasterized polygons")};
    return burnt;
}

std::array<double, 4> polygonBounds(const std::vector<PolygonFeature>& polygons) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::array<double, 4> box = {inf, inf, -inf, -inf};
    for (const PolygonFeature& p : polygons) {
        OGREnvelope envelope;
        OGR_G_GetEnvelope(static_cast<OGRGeometryH>(p.geometry.get()), &envelope);
        box = {std::min(box[0], envelope.MinX), std::min(box[1], envelope.MinY),
               std::max(box[2], envelope.MaxX), std::max(box[3], envelope.MaxY)};
    }
    return box;
}

}  // namespace sylva
