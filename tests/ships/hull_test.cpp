// Hulls: closed-mesh integrals against analytic solids, sampling, mesh files in and refused.
#include <fstream>

#include <gtest/gtest.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/hull_file.hpp"
#include "nearshore/ships/hull_mesh.hpp"
#include "nearshore/ships/hull_samples.hpp"
#include "ships_test_support.hpp"

namespace nearshore::ships {
namespace {

using testing::scratch_folder;
using testing::error_of;

TEST(HullMesh, BoxIntegralsAreTheSolidsExactly) {
  const double L = 20, B = 8, D = 4;
  const HullMesh box = box_barge(L, B, D);
  EXPECT_NO_THROW(require_closed_outward(box));
  const MeshMassProperties p = mesh_mass_properties(box);
  // Exact for a polyhedron: only round-off.
  EXPECT_NEAR(p.volume_m3, L * B * D, 1e-9);
  EXPECT_NEAR(p.centroid_m.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.centroid_m.z(), D / 2, 1e-12);
  const double V = L * B * D;
  EXPECT_NEAR(p.inertia_per_density_m5(0, 0), V * (B * B + D * D) / 12, 1e-7);
  EXPECT_NEAR(p.inertia_per_density_m5(1, 1), V * (L * L + D * D) / 12, 1e-7);
  EXPECT_NEAR(p.inertia_per_density_m5(2, 2), V * (L * L + B * B) / 12, 1e-7);
  EXPECT_NEAR(p.inertia_per_density_m5(0, 1), 0.0, 1e-8);
  EXPECT_NEAR(p.surface_area_m2, 2 * (L * B + L * D + B * D), 1e-9);
}

TEST(HullMesh, WigleyHullHasTheVolumeOfItsFormula) {
  const double L = 20, B = 2, T = 1.25, D = 2.5;
  const HullMesh hull = wigley_hull(L, B, T, D);
  EXPECT_NO_THROW(require_closed_outward(hull));
  // Below the waterline: B (2L/3) (2T/3) = 4 L B T / 9 (block coefficient 4/9); wall sides above:
  // B (2L/3) (D - T). The mesh is piecewise linear between 41 stations and 12 levels: its chords
  // cut the convex sections by O(1/n^2), well under 1 %.
  const double below = 4 * L * B * T / 9, above = B * 2 * L / 3 * (D - T);
  EXPECT_NEAR(mesh_mass_properties(hull).volume_m3, below + above, 0.01 * (below + above));
  const HullSamples samples = sample_hull(hull, 4000);
  EXPECT_NEAR(displaced_volume_m3(samples, T), below, 0.01 * below);
  EXPECT_NEAR(waterline_for_volume_m(samples, below), T, 0.01 * T);
}

TEST(HullMesh, TheTugIsClosedAndItsSamplesCloseTheSurface) {
  const HullMesh tug = harbour_tug();
  EXPECT_NO_THROW(require_closed_outward(tug));
  const MeshMassProperties p = mesh_mass_properties(tug);
  EXPECT_GT(p.volume_m3, 0.5 * 24 * 9 * 4.5);
  EXPECT_LT(p.volume_m3, 24 * 9 * 4.5);
  const HullSamples samples = sample_hull(tug, 3000);
  EXPECT_GE(samples.size(), 3000u);
  EXPECT_LT(samples.size(), 9000u);
  double area = 0.0;
  Eigen::Vector3d closure = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    area += samples.area_m2[i];
    closure += samples.area_m2[i] * samples.normal[i];
  }
  // sum A n = 0 over a closed surface (divergence theorem of a constant field): round-off only.
  EXPECT_NEAR(area, p.surface_area_m2, 1e-9 * area);
  EXPECT_LT(closure.norm(), 1e-10 * area);
}

TEST(HullMesh, ObjAndPlyFilesLoadToTheSameSolid) {
  const auto folder = scratch_folder();
  const HullMesh box = box_barge(12, 5, 3);
  write_hull_obj(folder / "box.obj", box);
  const HullMesh from_obj = load_hull_mesh(folder / "box.obj");
  EXPECT_NEAR(mesh_mass_properties(from_obj).volume_m3, 12 * 5 * 3, 1e-9);
  {
    std::ofstream ply(folder / "box.ply");
    ply << "ply\nformat ascii 1.0\nelement vertex " << box.vertices_m.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << box.triangles.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& v : box.vertices_m) ply << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : box.triangles) ply << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  const HullMesh from_ply = load_hull_mesh(folder / "box.ply");
  EXPECT_NEAR(mesh_mass_properties(from_ply).volume_m3, 12 * 5 * 3, 1e-4);
  // A hull with per-face vertices (as exporters write with flat normals) is welded and accepted.
  HullMesh split = box;
  split.vertices_m.clear();
  split.triangles.clear();
  for (const auto& t : box.triangles) {
    const int base = static_cast<int>(split.vertices_m.size());
    for (int k = 0; k < 3; ++k) split.vertices_m.push_back(box.vertices_m[t[k]]);
    split.triangles.push_back({base, base + 1, base + 2});
  }
  write_hull_obj(folder / "split.obj", split);
  EXPECT_NEAR(mesh_mass_properties(load_hull_mesh(folder / "split.obj")).volume_m3, 12 * 5 * 3, 1e-9);
}

TEST(HullMesh, OpenInvertedAndMissingMeshesAreRefusedNamingTheFile) {
  const auto folder = scratch_folder();
  HullMesh open = wigley_hull(20, 2, 1, 2);
  open.triangles.erase(open.triangles.begin() + 5);
  write_hull_obj(folder / "open.obj", open);
  std::string message = error_of([&] { load_hull_mesh(folder / "open.obj"); });
  EXPECT_NE(message.find("open.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("not closed"), std::string::npos) << message;

  HullMesh inverted = harbour_tug();
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  write_hull_obj(folder / "inverted.obj", inverted);
  message = error_of([&] { load_hull_mesh(folder / "inverted.obj"); });
  EXPECT_NE(message.find("inverted.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("inward"), std::string::npos) << message;

  HullMesh flipped_one = box_barge(10, 4, 2);
  std::swap(flipped_one.triangles[3][1], flipped_one.triangles[3][2]);
  write_hull_obj(folder / "flipped_one.obj", flipped_one);
  message = error_of([&] { load_hull_mesh(folder / "flipped_one.obj"); });
  EXPECT_NE(message.find("flipped_one.obj"), std::string::npos) << message;

  message = error_of([&] { load_hull_mesh(folder / "missing.obj"); });
  EXPECT_NE(message.find("missing.obj"), std::string::npos) << message;
  {
    std::ofstream garbage(folder / "garbage.obj");
    garbage << "this is not a mesh\n";
  }
  message = error_of([&] { load_hull_mesh(folder / "garbage.obj"); });
  EXPECT_NE(message.find("garbage.obj"), std::string::npos) << message;
}

}  // namespace
}  // namespace nearshore::ships
