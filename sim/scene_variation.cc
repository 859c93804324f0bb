#include "sim/scene_variation.h"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <set>
#include <stdexcept>

namespace sortcell::sim {
namespace {

bool IsObject(const mjModel* m, int body) {
  return body > 0 && m->body_jntnum[body] == 1 && m->jnt_type[m->body_jntadr[body]] == mjJNT_FREE;
}

Eigen::Vector3d RandomUnitVector(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d v;
  do {
    // One draw per statement: a constructor's arguments are evaluated in an unspecified order (GCC went
    // from the last, clang from the first). z, y, x is GCC's order, so the results of before stand.
    const double z = normal(rng);
    const double y = normal(rng);
    const double x = normal(rng);
    v = Eigen::Vector3d(x, y, z);
  } while (v.norm() < 1e-6);
  return v.normalized();
}

// An RGB colour (0-1) with its hue turned by `hue_deg` and its saturation and value scaled.
void JitterHsv(float* rgb, double hue_deg, double saturation, double value) {
  cv::Mat3f colour(1, 1, cv::Vec3f(rgb[0], rgb[1], rgb[2]));
  cv::cvtColor(colour, colour, cv::COLOR_RGB2HSV);  // H in degrees, S and V in 0-1.
  cv::Vec3f& hsv = colour(0, 0);
  hsv[0] = static_cast<float>(std::fmod(hsv[0] + hue_deg + 360.0, 360.0));
  hsv[1] = static_cast<float>(std::clamp(hsv[1] * saturation, 0.0, 1.0));
  hsv[2] = static_cast<float>(std::clamp(hsv[2] * value, 0.0, 1.0));
  cv::cvtColor(colour, colour, cv::COLOR_HSV2RGB);
  for (int k = 0; k < 3; ++k) rgb[k] = colour(0, 0)[k];
}

// Every object's materials (or, without one, its geoms' colours) jittered by one draw per object.
void JitterColours(mjModel* m, double jitter, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::set<int> done;  // A material shared by objects keeps its first object's draw.
  for (int b = 0; b < m->nbody; ++b) {
    if (!IsObject(m, b)) continue;
    const double hue = 25.0 * jitter * unit(rng), saturation = 1 + 0.3 * jitter * unit(rng);
    const double value = 1 + 0.3 * jitter * unit(rng);
    for (int g = 0; g < m->ngeom; ++g) {
      if (m->geom_bodyid[g] != b) continue;
      const int material = m->geom_matid[g];
      if (material < 0) {
        JitterHsv(m->geom_rgba + 4 * g, hue, saturation, value);
      } else if (done.insert(material).second) {
        float* rgba = m->mat_rgba + 4 * material;
        if (m->mat_texid[material] >= 0) {
          for (int k = 0; k < 3; ++k) rgba[k] = static_cast<float>(std::clamp(rgba[k] * value, 0.0, 1.0));
        } else {
          JitterHsv(rgba, hue, saturation, value);
        }
      }
    }
  }
}

}  // namespace

void ApplyVariation(Model& model, const SceneVariation& variation, std::mt19937_64& rng) {
  const std::string scene = "scene '" + model.source() + "': ";
  if (!(variation.friction_scale > 0)) throw std::invalid_argument(scene + "friction scale must be > 0");
  if (!(variation.mass_scale > 0)) throw std::invalid_argument(scene + "mass scale must be > 0");
  if (!(variation.camera_shift_m >= 0) || !(variation.camera_turn_rad >= 0)) {
    throw std::invalid_argument(scene + "camera jitter must be >= 0");
  }
  if (!(variation.colour_jitter >= 0 && variation.colour_jitter <= 1)) {
    throw std::invalid_argument(scene + "colour jitter must be in [0, 1]");
  }
  const int camera = model.Id(mjOBJ_CAMERA, variation.camera);
  mjModel* m = model.mutable_get();
  for (int g = 0; g < m->ngeom; ++g) {
    if (IsObject(m, m->geom_bodyid[g])) m->geom_friction[3 * g] *= variation.friction_scale;
  }
  for (int b = 0; b < m->nbody; ++b) {
    if (!IsObject(m, b)) continue;
    m->body_mass[b] *= variation.mass_scale;
    for (int k = 0; k < 3; ++k) m->body_inertia[3 * b + k] *= variation.mass_scale;
  }
  // Draws happen even at zero jitter, so the random stream does not depend on the jitter's size.
  const Eigen::Vector3d shift = variation.camera_shift_m * RandomUnitVector(rng);
  const Eigen::Vector3d axis = RandomUnitVector(rng);
  Eigen::Map<Eigen::Vector3d>(m->cam_pos + 3 * camera) += shift;
  const Eigen::Quaterniond q(m->cam_quat[4 * camera], m->cam_quat[4 * camera + 1], m->cam_quat[4 * camera + 2],
                             m->cam_quat[4 * camera + 3]);
  // The turn is about an axis in the camera's own frame (MuJoCo's quaternion is body-to-camera).
  const Eigen::Quaterniond turned = (q * Eigen::AngleAxisd(variation.camera_turn_rad, axis)).normalized();
  m->cam_quat[4 * camera] = turned.w();
  m->cam_quat[4 * camera + 1] = turned.x();
  m->cam_quat[4 * camera + 2] = turned.y();
  m->cam_quat[4 * camera + 3] = turned.z();
  if (variation.colour_jitter > 0) {
    // A stream of its own, seeded from a copy of the episode's: the colours take nothing from the
    // stream the objects' choice and poses are drawn from next, so a seed sets the same scene at any
    // jitter.
    std::mt19937_64 copy = rng;
    const uint64_t a = copy(), b = copy();
    std::seed_seq seq{static_cast<uint32_t>(a), static_cast<uint32_t>(a >> 32), static_cast<uint32_t>(b),
                      static_cast<uint32_t>(b >> 32), 0xC0102u};
    std::mt19937_64 colours(seq);
    JitterObjectColours(model, variation.colour_jitter, colours);
  }
  // Derived quantities that depend on masses (subtree masses, armature-free inertias at qpos0).
  mjData* d = mj_makeData(m);
  mj_setConst(m, d);
  mj_deleteData(d);
}

void JitterObjectColours(Model& model, double jitter, std::mt19937_64& rng) {
  if (!(jitter >= 0 && jitter <= 1)) {
    throw std::invalid_argument("scene '" + model.source() + "': colour jitter must be in [0, 1]");
  }
  JitterColours(model.mutable_get(), jitter, rng);
}

}  // namespace sortcell::sim
