// GeographicLib projection: lat/lon -> grid -> lat/lon to better than 1 mm, and the CRS WKT we
// write describes the same projection as GDAL/PROJ understands it.
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <ogr_spatialref.h>

#include <cmath>
#include <memory>
#include <random>

#include <fmt/core.h>

#include "nearshore/bathymetry/projection.hpp"

namespace nb = nearshore::bathymetry;

namespace {

nearshore::GridGeometry grid_over(const nearshore::MapProjection& projection, nearshore::LonLat centre) {
  nearshore::GridGeometry g;
  const nearshore::ProjectedPoint c = projection.forward(centre);
  g.columns = 1500;
  g.rows = 1000;
  g.spacing_m = 10.0;
  g.origin_x_m = std::floor((c.x_m - 7500.0) / 10.0) * 10.0;
  g.origin_y_m = std::floor((c.y_m - 5000.0) / 10.0) * 10.0;
  g.projection = projection.to_json();
  g.crs_wkt = nb::crs_wkt(projection);
  return g;
}

// Geodesic distance in metres between two places (Karney 2013).
double metres_between(nearshore::LonLat a, nearshore::LonLat b) {
  double s12 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(a.latitude_deg, a.longitude_deg, b.latitude_deg, b.longitude_deg, s12);
  return s12;
}

void expect_round_trip_below_1mm(const nearshore::MapProjection& projection, nearshore::LonLat centre) {
  const nearshore::GridGeometry g = grid_over(projection, centre);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> offset(-0.07, 0.07);
  double worst_m = 0;
  for (int k = 0; k < 2000; ++k) {
    const nearshore::LonLat place{centre.longitude_deg + offset(random), centre.latitude_deg + 0.7 * offset(random)};
    const nearshore::LonLat back = nearshore::lon_lat_of(g, nearshore::grid_position_of(g, place));
    worst_m = std::max(worst_m, metres_between(place, back));
  }
  // The bound is 1 mm; GeographicLib's series are exact to ~5 nm, so a failure here means
  // an inconsistency in our frame (origin, half-cell offset, hemisphere), not numerical error.
  EXPECT_LT(worst_m, 1e-3) << projection.describe();
  ::testing::Test::RecordProperty("worst_round_trip_m_" + projection.to_json().value("kind", std::string{}), fmt::format("{:.3e}", worst_m));
}

}  // namespace

TEST(Projection, UtmRoundTripThroughGridBelowOneMillimetre) {
  const nearshore::LonLat tacoma{-122.45, 47.28};
  const nearshore::MapProjection utm = nearshore::MapProjection::utm_for(tacoma);
  EXPECT_EQ(utm.to_json()["zone"], 10);
  EXPECT_EQ(utm.to_json()["north"], true);
  expect_round_trip_below_1mm(utm, tacoma);
  expect_round_trip_below_1mm(nearshore::MapProjection::utm_for({151.2, -33.85}), {151.2, -33.85});  // southern hemisphere
}

TEST(Projection, LocalTransverseMercatorRoundTripBelowOneMillimetre) {
  const nearshore::LonLat centre{121.695, 38.905};
  const nearshore::MapProjection tm = nearshore::MapProjection::local_transverse_mercator(centre);
  const nearshore::ProjectedPoint origin = tm.forward(centre);
  EXPECT_NEAR(origin.x_m, 0.0, 1e-9);
  EXPECT_NEAR(origin.y_m, 0.0, 1e-9);
  expect_round_trip_below_1mm(tm, centre);
}

TEST(Projection, JsonRoundTripKeepsTheProjection) {
  for (const auto& projection : {nearshore::MapProjection::utm(33, false), nearshore::MapProjection::local_transverse_mercator({10.7, 59.9})}) {
    const auto again = nearshore::MapProjection::from_json(projection.to_json(), "test");
    const auto a = projection.forward({10.75, 59.95}), b = again.forward({10.75, 59.95});
    EXPECT_EQ(a.x_m, b.x_m);
    EXPECT_EQ(a.y_m, b.y_m);
  }
  EXPECT_THROW(nearshore::MapProjection::from_json({{"kind", "mercator"}}, "test"), std::runtime_error);
}

TEST(Projection, CrsWktAgreesWithGdalWithinOneMillimetre) {
  // PROJ evaluates the same WKT independently (its own Poder/Engsager TM); within the harbour
  // the two agree to micrometres, so 1 mm flags a wrong datum, zone or origin in our WKT.
  for (const auto& projection : {nearshore::MapProjection::utm_for({-122.45, 47.28}),
                                 nearshore::MapProjection::local_transverse_mercator({-122.45, 47.28})}) {
    OGRSpatialReference wgs84, ours;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    ASSERT_EQ(ours.importFromWkt(nb::crs_wkt(projection).c_str()), OGRERR_NONE);
    ours.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> transform(OGRCreateCoordinateTransformation(&wgs84, &ours));
    ASSERT_TRUE(transform);
    for (const nearshore::LonLat p : {nearshore::LonLat{-122.50, 47.24}, nearshore::LonLat{-122.40, 47.31}, nearshore::LonLat{-122.45, 47.28}}) {
      double x = p.longitude_deg, y = p.latitude_deg;
      ASSERT_TRUE(transform->Transform(1, &x, &y));
      const nearshore::ProjectedPoint q = projection.forward(p);
      EXPECT_NEAR(x, q.x_m, 1e-3) << projection.describe();
      EXPECT_NEAR(y, q.y_m, 1e-3) << projection.describe();
    }
  }
}
