#pragma once
/// @file
/// Writing an imported object for MuJoCo 2.2: the MJCF fragment (models/objects/objects.inc.xml's
/// classes) and the visual mesh in MuJoCo's binary MSH format.

#include <filesystem>
#include <string>

#include "assets/object_geometry.h"
#include "assets/object_import.h"

namespace sortcell::assets {

/// Where the fragment's files will be (absolute; `texture` empty when there is none).
struct ObjectXmlFiles {
  std::filesystem::path visual;
  std::filesystem::path texture;
};

/// The fragment: assets (texture, material, visual mesh, one mesh per convex piece with its vertices
/// inline) and one free body `source.name` with the report's mass and the geometry's inertia.
/// `unit_density` is geometry.Mass(), the inertia scaled to the report's mass.
std::string ObjectXml(const ObjectSource& source, const ObjectGeometry& geometry, const ImportReport& report,
                      const MassProperties& unit_density, const ObjectXmlFiles& files);

/// MuJoCo's MSH: int32 counts (vertices, normals, texcoords, faces), then float32 vertices, normals,
/// texcoords and int32 faces. Normals and texcoords are written when the mesh has them.
void WriteMsh(const TriangleMesh& mesh, const std::filesystem::path& file);

}  // namespace sortcell::assets
