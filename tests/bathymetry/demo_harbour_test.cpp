// The demo harbour generator (foundation issue): what it writes, GDAL reads back at the right place.
#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;

namespace {
struct Closer {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using Dataset = std::unique_ptr<GDALDataset, Closer>;
}  // namespace

TEST(DemoHarbour, GeoTiffIsInTheSitesUtmZoneWithTheAnalyticDepths) {
  const auto folder = fresh_test_folder("");
  const nb::DemoHarbourOptions options;
  const nb::DemoHarbourFiles files = nb::write_demo_harbour(folder, options);
  GDALAllRegister();
  Dataset tif(GDALDataset::Open(files.depth_geotiff.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  ASSERT_TRUE(tif);
  EXPECT_EQ(tif->GetRasterXSize(), 200);  // 1600 m / 8 m
  EXPECT_EQ(tif->GetRasterYSize(), 150);  // 1200 m / 8 m
  ASSERT_NE(tif->GetSpatialRef(), nullptr);
  EXPECT_STREQ(tif->GetSpatialRef()->GetAuthorityCode(nullptr), "32651");  // 121.695 E, 38.9 N: zone 51N
  double gt[6];
  ASSERT_EQ(tif->GetGeoTransform(gt), CE_None);
  int zone = 0;
  bool north = true;
  double easting = 0, northing = 0;
  GeographicLib::UTMUPS::Forward(options.centre_latitude_deg, options.centre_longitude_deg, zone, north, easting, northing);
  // The grid's centre is the site's centre (the generator defines it so), to float-free precision.
  EXPECT_NEAR(gt[0] + 0.5 * 200 * gt[1], easting, 1e-6);
  EXPECT_NEAR(gt[3] + 0.5 * 150 * gt[5], northing, 1e-6);
  EXPECT_DOUBLE_EQ(gt[1], 8.0);
  EXPECT_DOUBLE_EQ(gt[5], -8.0);
  EXPECT_STREQ(tif->GetMetadataItem("NEARSHORE_DEPTH_SIGN"), "positive_down");
  // Pixel (column 100, line 30) has its centre at local x = 804 m, y = 1200 - 244 = 956 m.
  float value = 0;
  ASSERT_EQ(tif->GetRasterBand(1)->RasterIO(GF_Read, 100, 30, 1, 1, &value, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_FLOAT_EQ(value, static_cast<float>(nb::demo_harbour_depth_m(options, 804.0, 956.0)));
}

TEST(DemoHarbour, GeoJsonLayersAreWgs84AroundTheSiteWithStructureProperties) {
  const auto folder = fresh_test_folder("");
  const nb::DemoHarbourOptions options;
  const nb::DemoHarbourFiles files = nb::write_demo_harbour(folder, options);
  GDALAllRegister();
  for (const auto& path : {files.coastline_geojson, files.land_geojson, files.structures_geojson}) {
    Dataset vector(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    ASSERT_TRUE(vector) << path;
    OGRLayer* layer = vector->GetLayer(0);
    ASSERT_NE(layer->GetSpatialRef(), nullptr);
    EXPECT_TRUE(layer->GetSpatialRef()->IsGeographic());
    OGREnvelope extent;
    ASSERT_EQ(layer->GetExtent(&extent), OGRERR_NONE);
    // Within the 1.6 km x 1.2 km site: ~0.02 degrees of longitude at 39 N, 0.011 of latitude.
    EXPECT_GT(extent.MinX, options.centre_longitude_deg - 0.01);
    EXPECT_LT(extent.MaxX, options.centre_longitude_deg + 0.01);
    EXPECT_GT(extent.MinY, options.centre_latitude_deg - 0.006);
    EXPECT_LT(extent.MaxY, options.centre_latitude_deg + 0.006);
  }
  Dataset structures(GDALDataset::Open(files.structures_geojson.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  OGRLayer* layer = structures->GetLayer(0);
  EXPECT_EQ(layer->GetFeatureCount(), 4);  // two breakwater arms, the detached breakwater, the quay front
  int arms = 0;
  for (auto& feature : *layer) {
    const std::string category = feature->GetFieldAsString("category");
    if (category == "rubble_mound_breakwater") {
      ++arms;
      EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("crest_width_m"), 10.0);
      EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("crest_elevation_m"), 3.0);
    } else {
      EXPECT_EQ(category, "vertical_quay");
      EXPECT_STREQ(feature->GetFieldAsString("name"), "quay");
    }
  }
  EXPECT_EQ(arms, 3);
}
