// Importing a user's object: a URDF with a textured visual mesh and a two-piece convex decomposition,
// its inertia against two boxes of known size (and against MuJoCo's compile of the fragment), the
// cache, and one-line errors naming the file for bad input.
#include "assets/mass_properties.h"
#include "assets/mesh_reader.h"
#include "assets/object_import.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <Eigen/Eigenvalues>

#include "files/data_dir.h"
#include "sim/scene_composer.h"
#include "temp_dir.h"
#include "user_objects.h"

namespace {

namespace assets = sortcell::assets;
using sortcell_test::WriteUserObject;

// A solid box's inertia about its own centre, and moved to `about` (parallel axes).
Eigen::Matrix3d BoxInertia(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double density,
                           const Eigen::Vector3d& about) {
  const Eigen::Vector3d s = hi - lo, c = (hi + lo) / 2;
  const double m = density * s.prod();
  Eigen::Matrix3d I =
      Eigen::Vector3d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y())
          .asDiagonal();
  I *= m / 12;
  const Eigen::Vector3d d = c - about;
  return I + m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

std::string ImportError(const assets::ObjectSource& source, const std::filesystem::path& cache) {
  try {
    assets::ImportObject(source, cache);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

TEST(ObjectImport, AUrdfWithATextureAndTwoConvexPieces) {
  sortcell_test::TempDir dir;
  const auto user = WriteUserObject(dir.path() / "user");
  assets::ObjectSource source;
  source.name = "thing";
  source.urdf = user.urdf;
  const auto imported = assets::ImportObject(source, dir.path() / "cache");
  const auto& r = imported.report;
  EXPECT_FALSE(imported.from_cache);
  EXPECT_EQ(r.collision_pieces, 2);  // the body and the handle, not one hull around both
  EXPECT_NEAR(r.mass, 0.3, 1e-12);
  const double v1 = 0.06 * 0.04 * 0.10, v2 = 0.02 * 0.02 * 0.04;
  EXPECT_NEAR(r.volume, v1 + v2, 1e-9);
  EXPECT_TRUE(r.size.isApprox(Eigen::Vector3d(0.09, 0.04, 0.10), 1e-6)) << r.size.transpose();

  // In the body frame (origin at the base centre of the collision geometry, x from -0.045): the two
  // boxes' inertia about the common centre of mass.
  const double density = 0.3 / (v1 + v2);
  const Eigen::Vector3d lo1(-0.045, -0.02, 0), hi1(0.015, 0.02, 0.10), lo2(0.025, -0.01, 0.03), hi2(0.045, 0.01, 0.07);
  const Eigen::Vector3d com = (v1 * (lo1 + hi1) / 2 + v2 * (lo2 + hi2) / 2) / (v1 + v2);
  EXPECT_TRUE(r.com.isApprox(com, 1e-6)) << r.com.transpose();
  const Eigen::Matrix3d I = BoxInertia(lo1, hi1, density, com) + BoxInertia(lo2, hi2, density, com);
  const Eigen::Vector3d expected = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
  EXPECT_TRUE(r.principal_inertia.isApprox(expected, 1e-6))
      << r.principal_inertia.transpose() << " vs " << expected.transpose();
  EXPECT_LT(r.principal_inertia.maxCoeff(), 1e-3);  // not the URDF's placeholder

  // Written into the cache (texture converted to PNG), nothing beside the user's files.
  const auto cache_dir = imported.fragment.parent_path();
  EXPECT_TRUE(std::filesystem::exists(cache_dir / "texture.png"));
  EXPECT_TRUE(std::filesystem::exists(cache_dir / "visual.msh"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "user" / "meshes" / "skin.png"));
  EXPECT_TRUE(assets::ImportObject(source, dir.path() / "cache").from_cache);

  // MuJoCo compiles the fragment in the cell with the same mass, centre of mass and inertia.
  const auto model = sortcell::sim::LoadComposedCell(std::filesystem::path(SORTCELL_SOURCE_DIR) / "models",
                                                     {imported.fragment}, "test");
  const int body = model.Id(mjOBJ_BODY, "thing");
  EXPECT_NEAR(model->body_mass[body], 0.3, 1e-9);
  Eigen::Vector3d mj_inertia(model->body_inertia[3 * body], model->body_inertia[3 * body + 1],
                             model->body_inertia[3 * body + 2]);
  std::sort(mj_inertia.data(), mj_inertia.data() + 3);
  EXPECT_TRUE(mj_inertia.isApprox(expected, 1e-5)) << mj_inertia.transpose();
  int colliding = 0;
  for (int g = 0; g < model->ngeom; ++g) colliding += model->geom_bodyid[g] == body && model->geom_contype[g] != 0;
  EXPECT_EQ(colliding, 2);
}

// A ball given as URDF primitives: its footprint is its equator (what the fingers close across), its
// inertia a solid sphere's, its origin at its base.
TEST(ObjectImport, ASpherePrimitiveIsAsWideAsItsEquator) {
  sortcell_test::TempDir dir;
  const std::filesystem::path urdf = dir.path() / "ball.urdf";
  std::ofstream(urdf)
      << "<robot name='ball'><link name='ball'>"
         "<inertial><mass value='0.2'/><inertia ixx='1e-3' iyy='1e-3' izz='1e-3' ixy='0' ixz='0' iyz='0'/></inertial>"
         "<visual><geometry><sphere radius='0.035'/></geometry></visual>"
         "<collision><geometry><sphere radius='0.035'/></geometry></collision>"
         "</link></robot>";
  assets::ObjectSource source;
  source.name = "ball";
  source.urdf = urdf;
  const auto r = assets::ImportObject(source, dir.path() / "cache").report;
  EXPECT_EQ(r.collision_pieces, 1);
  EXPECT_NEAR(r.grip_width, 0.07, 1e-3);
  EXPECT_TRUE(r.size.isApprox(Eigen::Vector3d::Constant(0.07), 1e-3)) << r.size.transpose();
  EXPECT_NEAR(r.volume, 4.0 / 3.0 * M_PI * std::pow(0.035, 3), 1e-9);
  const double solid = 0.4 * 0.2 * 0.035 * 0.035;  // 2/5 m r^2, never the URDF's 1e-3
  EXPECT_TRUE(r.principal_inertia.isApprox(Eigen::Vector3d::Constant(solid), 1e-3)) << r.principal_inertia.transpose();
  EXPECT_NEAR(r.com.z(), 0.035, 1e-6);  // the origin at its base
}

TEST(ObjectImport, BoxMassPropertiesAndMinimumWidth) {
  const auto hull = assets::ConvexHull({{0, 0, 0},
                                        {0.2, 0, 0},
                                        {0, 0.1, 0},
                                        {0.2, 0.1, 0},
                                        {0, 0, 0.05},
                                        {0.2, 0, 0.05},
                                        {0, 0.1, 0.05},
                                        {0.2, 0.1, 0.05},
                                        {0.1, 0.05, 0.02}});
  EXPECT_EQ(hull.vertices.size(), 8u);  // the inner point is not on the hull
  EXPECT_TRUE(assets::IsClosedAndOriented(hull));
  const auto m = assets::MassPropertiesOf(hull);
  EXPECT_NEAR(m.volume, 0.2 * 0.1 * 0.05, 1e-12);
  EXPECT_TRUE(m.centroid.isApprox(Eigen::Vector3d(0.1, 0.05, 0.025), 1e-9));
  EXPECT_NEAR(m.inertia(0, 0), m.volume * (0.1 * 0.1 + 0.05 * 0.05) / 12, 1e-12);
  EXPECT_NEAR(m.inertia(2, 2), m.volume * (0.2 * 0.2 + 0.1 * 0.1) / 12, 1e-12);
  EXPECT_NEAR(assets::MinimumWidth({{0, 0}, {0.2, 0}, {0.2, 0.1}, {0, 0.1}}), 0.1, 1e-6);
}

TEST(ObjectImport, BadInputIsOneLineNamingTheFile) {
  sortcell_test::TempDir dir;
  const auto cache = dir.path() / "cache";
  const auto user = WriteUserObject(dir.path() / "zero", "0");
  assets::ObjectSource source{"thing", user.urdf, {}, {}, {}, 1, {}};
  std::string e = ImportError(source, cache);
  EXPECT_NE(e.find(user.urdf.string()), std::string::npos) << e;
  EXPECT_NE(e.find("mass"), std::string::npos) << e;

  const auto ok = WriteUserObject(dir.path() / "big");
  source.urdf = ok.urdf;
  source.scale = 100;  // a file in centimetres read as metres
  e = ImportError(source, cache);
  EXPECT_NE(e.find("m across"), std::string::npos) << e;
  EXPECT_NE(e.find("scale"), std::string::npos) << e;

  source.scale = 1;
  std::ofstream(ok.collision) << "solid x\nfacet normal 0 0 0\n outer loop\n vertex nan 0 0\n";
  e = ImportError(source, cache);
  EXPECT_NE(e.find(ok.collision.string()), std::string::npos) << e;

  const auto broken_texture = WriteUserObject(dir.path() / "texture");
  std::ofstream(broken_texture.texture) << "not a jpeg";
  source.urdf = broken_texture.urdf;
  e = ImportError(source, cache);
  EXPECT_NE(e.find("texture '" + broken_texture.texture.string() + "': does not decode"), std::string::npos) << e;

  const auto missing = WriteUserObject(dir.path() / "missing");
  std::filesystem::remove(missing.visual);
  source.urdf = missing.urdf;
  e = ImportError(source, cache);
  EXPECT_NE(e.find(missing.visual.string() + "' not found"), std::string::npos) << e;

  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_THROW(assets::ReadMeshFromMemory("v 1 2\nf 1 2 3 4 5\n", "obj", "junk.obj"), std::invalid_argument);
  // A failed import leaves nothing behind in the cache.
  for (const auto& entry : std::filesystem::directory_iterator(cache)) ADD_FAILURE() << entry.path();
}

}  // namespace
