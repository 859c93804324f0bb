#pragma once
/// @file
/// Reading and writing object and scene clouds as PCD, with the checks PCL does not make.

#include <filesystem>

#include "perception/cloud.h"

namespace sortcell::perception {

/// Reads a PCD with x, y, z and colour ("rgb" or "rgba", as PCL's OpenNI grabber writes XYZRGBA),
/// any PCD encoding. With `organized`, the cloud must be organized (height > 1), as a depth camera
/// delivers it.
/// @throws std::invalid_argument "PCD '<file>': <what>" for a missing or unreadable file, a missing
///         field, an empty cloud, or an unorganized cloud when one is required.
Cloud::Ptr LoadCloud(const std::filesystem::path& file, bool organized);

/// Writes binary_compressed PCD. @throws std::runtime_error naming the file on failure.
void SaveCloud(const std::filesystem::path& file, const Cloud& cloud);

}  // namespace sortcell::perception
