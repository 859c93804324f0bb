// Every model and scene compiles in MuJoCo 2.2 without warnings; the URDF parses with urdfdom and
// agrees with the MJCF and the D-H table; object sets compose into the cell.
#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "files/object_set.h"
#include "robot/ur5_dh.h"
#include "sim/model.h"
#include "sim/scene_composer.h"
#include "source_tree.h"

namespace fs = std::filesystem;
using sortcell::sim::Model;

namespace {

using sortcell_test::kRoot;
const std::vector<std::string> kArmJoints = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                             "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
const std::vector<std::string> kArmBodies = {"shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
                                             "wrist_2_link",  "wrist_3_link",   "flange"};

std::vector<fs::path> XmlFiles(bool fragments) {
  std::vector<fs::path> files;
  for (const char* dir : {"models", "scenes"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / dir)) {
      const std::string name = entry.path().filename().string();
      if (entry.path().extension() != ".xml") continue;
      const bool is_fragment = name.size() > 8 && name.substr(name.size() - 8) == ".inc.xml";
      if (is_fragment == fragments) files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string ReadText(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every produce instance: a textured visual mesh over a collision primitive, and instances of one
// category differ in size and colour.
TEST(ModelFiles, ProduceInstancesAreTexturedAndVary) {
  const auto produce = sortcell::files::LoadObjectSet(kRoot / "scenes/objects/produce.yaml");
  std::vector<fs::path> models;
  for (const auto& o : produce.objects) models.push_back(o.model);
  const Model scene = sortcell::sim::LoadComposedCell(kRoot / "models", models, "produce");
  std::map<std::string, std::vector<double>> widths;
  std::map<std::string, std::set<std::vector<unsigned char>>> first_texels;
  for (const auto& o : produce.objects) {
    SCOPED_TRACE(o.name);
    const int visual = scene.Id(mjOBJ_GEOM, o.name);
    EXPECT_EQ(scene->geom_type[visual], mjGEOM_MESH);
    EXPECT_EQ(scene->geom_contype[visual], 0);  // Seen, not touched.
    const int material = scene->geom_matid[visual];
    ASSERT_GE(material, 0);
    const int texture = scene->mat_texid[material];
    ASSERT_GE(texture, 0);
    EXPECT_EQ(scene->tex_type[texture], mjTEXTURE_2D);
    const unsigned char* rgb = scene->tex_rgb + scene->tex_adr[texture];
    first_texels[o.category].insert(std::vector<unsigned char>(rgb, rgb + 3 * 64));
    // The collision hull: a primitive touching the world.
    const int hull = scene.Id(mjOBJ_GEOM, o.name + "_hull");
    EXPECT_NE(scene->geom_type[hull], mjGEOM_MESH);
    EXPECT_NE(scene->geom_contype[hull], 0);
    widths[o.category].push_back(2 * std::min(scene->geom_size[3 * hull], scene->geom_size[3 * hull + 1]));
  }
  for (const auto& [category, w] : widths) {
    EXPECT_GE(*std::max_element(w.begin(), w.end()) / *std::min_element(w.begin(), w.end()), 1.08) << category;
    EXPECT_EQ(first_texels[category].size(), w.size()) << category << ": two instances share a texture";
  }
}

}  // namespace

TEST(ModelFiles, EveryMainFileCompilesWithoutWarningsAndSteps) {
  const auto files = XmlFiles(/*fragments=*/false);
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    // With the models' textures found by name, as sortcell loads every scene (app::LoadScene).
    const Model model = Model::FromFile(file.string(), sortcell::sim::ModelTextures(kRoot / "models"));
    EXPECT_EQ(model.compile_warning(), "");
    sortcell::sim::Data data(model);
    const auto status = sortcell::sim::Step(model, data, 250);
    EXPECT_EQ(status.code, sortcell::sim::StepStatus::kOk) << status.detail;
  }
}

TEST(ModelFiles, EveryFragmentIsIncludedOrListedInAnObjectSet) {
  std::string referencing;  // All text that can name a fragment.
  for (const auto& f : XmlFiles(false)) referencing += ReadText(f);
  for (const auto& f : XmlFiles(true)) referencing += ReadText(f);
  for (const auto& f : fs::directory_iterator(kRoot / "scenes" / "objects")) referencing += ReadText(f.path());
  referencing += ReadText(kRoot / "sim" / "scene_composer.cc");
  // Named as a whole file name: in an include's quotes or at the end of a YAML value.
  const auto named = [&referencing](const std::string& name) {
    for (size_t at = referencing.find(name); at != std::string::npos; at = referencing.find(name, at + 1)) {
      const size_t end = at + name.size();
      const bool starts = at == 0 || std::string("\"'/ ").find(referencing[at - 1]) != std::string::npos;
      const bool ends =
          end == referencing.size() || std::string("\"'\n\r,} ").find(referencing[end]) != std::string::npos;
      if (starts && ends) return true;
    }
    return false;
  };
  for (const auto& fragment : XmlFiles(true)) {
    const std::string name = fragment.filename().string();
    EXPECT_TRUE(named(name)) << name << " is included nowhere";
  }
}

TEST(ModelFiles, Ur5MjcfBodiesFollowTheDhTable) {
  const Model model = Model::FromFile((kRoot / "models/ur5/ur5.xml").string());
  for (size_t i = 0; i + 1 < kArmBodies.size(); ++i) {
    SCOPED_TRACE(kArmBodies[i + 1]);
    const int b = model.Id(mjOBJ_BODY, kArmBodies[i + 1]);
    const auto& dh = sortcell::robot::kUr5Dh[i];
    EXPECT_NEAR(model->body_pos[3 * b + 0], dh.a, 1e-12);
    EXPECT_NEAR(model->body_pos[3 * b + 1], 0.0, 1e-12);
    EXPECT_NEAR(model->body_pos[3 * b + 2], dh.d, 1e-12);
    const Eigen::Quaterniond expected(Eigen::AngleAxisd(dh.alpha, Eigen::Vector3d::UnitX()));
    const Eigen::Quaterniond actual(model->body_quat[4 * b], model->body_quat[4 * b + 1], model->body_quat[4 * b + 2],
                                    model->body_quat[4 * b + 3]);
    EXPECT_LT(actual.angularDistance(expected), 1e-12);
  }
  // Joint limits in radians (the compiler's angle setting), motors torque-limited.
  for (size_t j = 0; j < kArmJoints.size(); ++j) {
    const int id = model.Id(mjOBJ_JOINT, kArmJoints[j]);
    const double limit = kArmJoints[j] == "elbow_joint" ? M_PI : 2 * M_PI;
    EXPECT_NEAR(model->jnt_range[2 * id + 1], limit, 1e-12) << kArmJoints[j];
    EXPECT_TRUE(model->jnt_limited[id]);
    EXPECT_NEAR(model->actuator_ctrlrange[2 * j + 1], j < 3 ? 150.0 : 28.0, 1e-12);
    EXPECT_EQ(model->actuator_trnid[2 * j], id);
  }
}

TEST(ModelFiles, UrdfParsesAndAgreesWithTheMjcf) {
  const auto urdf = urdf::parseURDFFile((kRoot / "models/ur5/ur5.urdf").string());
  ASSERT_TRUE(urdf) << "urdfdom could not parse models/ur5/ur5.urdf";
  const Model mjcf = Model::FromFile((kRoot / "models/ur5/ur5.xml").string());
  for (size_t j = 0; j < kArmJoints.size(); ++j) {
    SCOPED_TRACE(kArmJoints[j]);
    const auto joint = urdf->getJoint(kArmJoints[j]);
    ASSERT_TRUE(joint);
    EXPECT_EQ(joint->type, urdf::Joint::REVOLUTE);
    EXPECT_EQ(joint->child_link_name, kArmBodies[j]);
    const auto& dh = sortcell::robot::kUr5Dh;
    const auto& p = joint->parent_to_joint_origin_transform.position;
    const double a = j == 0 ? 0.0 : dh[j - 1].a, d = j == 0 ? 0.0 : dh[j - 1].d;
    EXPECT_NEAR(p.x, a, 1e-12);
    EXPECT_NEAR(p.y, 0.0, 1e-12);
    EXPECT_NEAR(p.z, d, 1e-12);
    double roll, pitch, yaw;
    joint->parent_to_joint_origin_transform.rotation.getRPY(roll, pitch, yaw);
    EXPECT_NEAR(roll, j == 0 ? 0.0 : dh[j - 1].alpha, 1e-12);
    EXPECT_NEAR(joint->limits->effort, j < 3 ? 150.0 : 28.0, 1e-12);
    EXPECT_NEAR(joint->limits->velocity, M_PI, 1e-12);
    const int id = mjcf.Id(mjOBJ_JOINT, kArmJoints[j]);
    EXPECT_NEAR(joint->limits->upper, mjcf->jnt_range[2 * id + 1], 1e-12);
    // The inertials, field by field: mass, centre of mass and the inertia's diagonal, in the same frames.
    const auto link = urdf->getLink(kArmBodies[j]);
    const int body = mjcf.Id(mjOBJ_BODY, kArmBodies[j]);
    EXPECT_NEAR(link->inertial->mass, mjcf->body_mass[body], 1e-12);
    const auto& com = link->inertial->origin.position;
    EXPECT_NEAR(com.x, mjcf->body_ipos[3 * body], 1e-12);
    EXPECT_NEAR(com.y, mjcf->body_ipos[3 * body + 1], 1e-12);
    EXPECT_NEAR(com.z, mjcf->body_ipos[3 * body + 2], 1e-12);
    EXPECT_NEAR(link->inertial->ixx, mjcf->body_inertia[3 * body], 1e-12);
    EXPECT_NEAR(link->inertial->iyy, mjcf->body_inertia[3 * body + 1], 1e-12);
    EXPECT_NEAR(link->inertial->izz, mjcf->body_inertia[3 * body + 2], 1e-12);
    EXPECT_NEAR(mjcf->body_iquat[4 * body], 1.0, 1e-12);  // Not turned: the diagonal is the diagonal.
  }
  const auto flange = urdf->getJoint("flange_joint");
  ASSERT_TRUE(flange);
  EXPECT_NEAR(flange->parent_to_joint_origin_transform.position.z, sortcell::robot::kUr5Dh[5].d, 1e-12);
}

// The URDF's <visual> elements are the MJCF arm's geoms, one by one in the same order: kind, radius,
// length, centre and axis. URDF 1.0 has no capsule: a visual named *_capsule is the MJCF capsule around
// that cylinder.
TEST(ModelFiles, UrdfVisualsAreTheMjcfArmsGeoms) {
  const auto urdf = urdf::parseURDFFile((kRoot / "models/ur5/ur5.urdf").string());
  ASSERT_TRUE(urdf) << "urdfdom could not parse models/ur5/ur5.urdf";
  const Model mjcf = Model::FromFile((kRoot / "models/ur5/ur5.xml").string());
  std::vector<std::string> links = {"base_link"};
  // Not the flange: its geom is the tool slot's plate (models/ur5/flange_tool.inc.xml), not the arm's.
  links.insert(links.end(), kArmBodies.begin(), kArmBodies.end() - 1);
  for (const std::string& name : links) {
    SCOPED_TRACE(name);
    const auto link = urdf->getLink(name);
    ASSERT_TRUE(link);
    const int body = mjcf.Id(mjOBJ_BODY, name);
    std::vector<int> geoms;
    for (int g = 0; g < mjcf->ngeom; ++g) {
      if (mjcf->geom_bodyid[g] == body) geoms.push_back(g);
    }
    ASSERT_EQ(link->visual_array.size(), geoms.size());
    for (size_t i = 0; i < geoms.size(); ++i) {
      const int g = geoms[i];
      const urdf::Visual& visual = *link->visual_array[i];
      SCOPED_TRACE(visual.name);
      ASSERT_EQ(visual.geometry->type, urdf::Geometry::CYLINDER);
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*visual.geometry);
      const std::string suffix = "_capsule";
      const bool capsule = visual.name.size() > suffix.size() &&
                           visual.name.compare(visual.name.size() - suffix.size(), suffix.size(), suffix) == 0;
      EXPECT_EQ(mjcf->geom_type[g], capsule ? mjGEOM_CAPSULE : mjGEOM_CYLINDER);
      EXPECT_NEAR(cylinder.radius, mjcf->geom_size[3 * g], 1e-12);
      EXPECT_NEAR(cylinder.length, 2 * mjcf->geom_size[3 * g + 1], 1e-12);
      const auto& p = visual.origin.position;
      EXPECT_NEAR(p.x, mjcf->geom_pos[3 * g], 1e-12);
      EXPECT_NEAR(p.y, mjcf->geom_pos[3 * g + 1], 1e-12);
      EXPECT_NEAR(p.z, mjcf->geom_pos[3 * g + 2], 1e-12);
      const auto& r = visual.origin.rotation;
      const Eigen::Vector3d axis_urdf = Eigen::Quaterniond(r.w, r.x, r.y, r.z) * Eigen::Vector3d::UnitZ();
      const mjtNum* quat = mjcf->geom_quat + 4 * g;
      const Eigen::Vector3d axis_mjcf =
          Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]) * Eigen::Vector3d::UnitZ();
      EXPECT_NEAR(std::abs(axis_urdf.dot(axis_mjcf)), 1.0, 1e-12);
    }
  }
}

TEST(ModelFiles, DefaultCellHoldsThePaperObjectsBinsAndKinect) {
  const Model cell = Model::FromFile((kRoot / "scenes/cell.xml").string());
  EXPECT_EQ(sortcell::sim::FreeBodyNames(cell),
            (std::vector<std::string>{"bottle1", "cup", "ball", "bottle2", "bottle3", "box"}));
  for (const char* bin : {"bin_bottle", "bin_cup", "bin_ball", "bin_others"}) {
    EXPECT_NO_THROW(cell.Id(mjOBJ_BODY, bin));
    EXPECT_NO_THROW(cell.Id(mjOBJ_SITE, bin));
  }
  const int kinect = cell.Id(mjOBJ_CAMERA, "kinect");
  const double fy = 240.0 / std::tan(0.5 * cell->cam_fovy[kinect] * M_PI / 180.0);
  EXPECT_NEAR(fy, 525.0, 1.0);
  EXPECT_GE(cell->vis.global.offwidth, 640);
  EXPECT_EQ(cell->vis.quality.offsamples, 0);  // No MSAA for the sensor.
  EXPECT_EQ(cell->opt.cone, mjCONE_ELLIPTIC);
  EXPECT_EQ(cell->neq, 0);  // Grasps are held by friction, never by constraints.
  EXPECT_NO_THROW(cell.Id(mjOBJ_SITE, "tcp"));
}

TEST(ModelFiles, ObjectSetsComposeIntoTheCell) {
  const auto paper = sortcell::files::LoadObjectSet(kRoot / "scenes/objects/paper.yaml");
  EXPECT_EQ(paper.Categories(), (std::vector<std::string>{"bottle", "cup", "ball", "others"}));
  const auto produce = sortcell::files::LoadObjectSet(kRoot / "scenes/objects/produce.yaml");
  EXPECT_EQ(produce.Categories().size(), 10u);
  std::map<std::string, int> instances;
  for (const auto& o : produce.objects) ++instances[o.category];
  for (const auto& [category, count] : instances) EXPECT_GE(count, 6) << category;

  for (const auto* set : {&paper, &produce}) {
    std::vector<fs::path> models;
    for (const auto& o : set->objects) models.push_back(o.model);
    const Model scene = sortcell::sim::LoadComposedCell(kRoot / "models", models, set->source.string());
    EXPECT_EQ(scene.compile_warning(), "");
    const auto bodies = sortcell::sim::FreeBodyNames(scene);
    ASSERT_EQ(bodies.size(), set->objects.size());
    for (size_t i = 0; i < bodies.size(); ++i) EXPECT_EQ(bodies[i], set->objects[i].name);
    sortcell::sim::Data data(scene);
    EXPECT_EQ(sortcell::sim::Step(scene, data, 100).code, sortcell::sim::StepStatus::kOk);
  }
}
