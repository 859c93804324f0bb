#pragma once
// A user's object written from scratch for import tests: a textured cube as the visual OBJ (with its
// MTL and a JPEG texture), a collision STL holding two disconnected boxes (a body and a "handle"),
// and a one-link URDF naming both with an origin and a mass (the cube stands inside the body box, as
// a scan's visual and collision meshes share their frame).
#include <opencv2/core.hpp>
#include <turbojpeg.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace sortcell_test {

// An axis-aligned box [lo, hi] as 12 outward triangles in ASCII STL facets.
inline std::string StlBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto corner = [&](int k) {
    return Eigen::Vector3d(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  };
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  std::string text;
  for (const auto& f : faces) {
    text += "facet normal 0 0 0\n outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = corner(f[k]);
      text += "  vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
    }
    text += " endloop\nendfacet\n";
  }
  return text;
}

// A cube of side `side` centred at the origin, each face mapped onto the whole texture.
inline std::string ObjCube(double side) {
  const double h = side / 2;
  std::string obj = "mtllib cube.mtl\no cube\n";
  for (int k = 0; k < 8; ++k) {
    obj += "v " + std::to_string(k & 1 ? h : -h) + " " + std::to_string(k & 2 ? h : -h) + " " +
           std::to_string(k & 4 ? h : -h) + "\n";
  }
  obj += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl skin\n";
  const int quads[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
  for (const auto& q : quads) {
    obj += "f " + std::to_string(q[0]) + "/1 " + std::to_string(q[1]) + "/2 " + std::to_string(q[2]) + "/3 " +
           std::to_string(q[3]) + "/4\n";
  }
  return obj;
}

struct UserObject {
  std::filesystem::path urdf, visual, collision, texture;
};

// A JPEG of a continuous BGR or grey image, as scanned objects' textures come (the product only reads them).
inline void WriteJpeg(const std::filesystem::path& file, const cv::Mat& bgr) {
  tjhandle encoder = tjInitCompress();
  unsigned char* jpeg = nullptr;
  unsigned long size = 0;
  const bool grey = bgr.channels() == 1;
  const int status = tjCompress2(encoder, bgr.data, bgr.cols, static_cast<int>(bgr.step), bgr.rows,
                                 grey ? TJPF_GRAY : TJPF_BGR, &jpeg, &size, grey ? TJSAMP_GRAY : TJSAMP_420, 90, 0);
  tjDestroy(encoder);
  if (status != 0) throw std::runtime_error("cannot encode " + file.string());
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(jpeg), static_cast<std::streamsize>(size));
  tjFree(jpeg);
}

// Writes the object into `dir`: collision boxes 0.06 x 0.04 x 0.10 m (body) and 0.02 x 0.02 x 0.04 m
// (handle, 1 cm beside it), mass `mass` (text, so tests can write bad values).
inline UserObject WriteUserObject(const std::filesystem::path& dir, const std::string& mass = "0.3") {
  std::filesystem::create_directories(dir / "meshes");
  UserObject o{dir / "thing.urdf", dir / "meshes" / "cube.obj", dir / "meshes" / "pieces.stl",
               dir / "meshes" / "skin.jpg"};
  std::ofstream(o.visual) << ObjCube(0.05);
  std::ofstream(dir / "meshes" / "cube.mtl") << "newmtl skin\nmap_Kd skin.jpg \n";
  WriteJpeg(o.texture, cv::Mat(64, 64, CV_8UC3, cv::Scalar(40, 60, 200)));
  std::ofstream(o.collision) << "solid pieces\n"
                             << StlBox({-0.03, -0.02, 0}, {0.03, 0.02, 0.10})
                             << StlBox({0.04, -0.01, 0.03}, {0.06, 0.01, 0.07}) << "endsolid pieces\n";
  std::ofstream(o.urdf)
      << "<robot name=\"thing\"><link name=\"base_link\">\n"
         "<visual><origin xyz=\"0.1 0.2 0.35\" rpy=\"0 0 0\"/><geometry><mesh filename=\"meshes/cube.obj\"/>"
         "</geometry></visual>\n"
         "<collision><origin xyz=\"0.1 0.2 0.3\" rpy=\"0 0 0\"/><geometry><mesh filename=\"meshes/pieces.stl\" "
         "scale=\"1 1 1\"/></geometry></collision>\n"
         "<inertial><mass value=\"" +
             mass +
             "\"/><inertia ixx=\"1e-3\" ixy=\"0\" ixz=\"0\" iyy=\"1e-3\" "
             "iyz=\"0\" izz=\"1e-3\"/></inertial>\n</link></robot>\n";
  return o;
}

// An object set of the one object `urdf` (category cup), written into `dir`.
inline std::string SetWith(const std::filesystem::path& dir, const std::string& urdf) {
  const auto set = dir / "set.yaml";
  std::ofstream(set) << "name: mine\nobjects:\n  - {name: thing, category: cup, instance: thing, urdf: " << urdf
                     << "}\n";
  return set.string();
}

}  // namespace sortcell_test
