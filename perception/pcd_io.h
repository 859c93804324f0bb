#pragma once
/// @file
/// Reading and writing object and scene clouds as PCD, with the checks PCL does not make.

#include <filesystem>
#include <vector>

#include "perception/cloud.h"

namespace sortcell::perception {

/// Reads a PCD with x, y, z and colour ("rgb" or "rgba", as PCL's OpenNI grabber writes XYZRGBA),
/// any PCD encoding. With `organized`, the cloud must be organized (height > 1), as a depth camera
/// delivers it.
/// @throws std::invalid_argument "PCD '<file>': <what>" for a missing or unreadable file, a missing
///         field, an empty cloud, or an unorganized cloud when one is required.
Cloud::Ptr LoadCloud(const std::filesystem::path& file, bool organized);

/// The ground truth of a labelled mOSD capture (organized XYZRGB + a uint32 "label" per point): an object
/// id per point, 0 for no depth and the table (labels 1-9), k for (parts of) object k (labels 10k-10k+9).
/// @throws std::invalid_argument "PCD '<file>': <what>" if it cannot be read or has no "label" field.
std::vector<int> LoadMosdObjectIds(const std::filesystem::path& file);

/// Writes binary_compressed PCD. @throws std::runtime_error naming the file on failure.
void SaveCloud(const std::filesystem::path& file, const Cloud& cloud);

}  // namespace sortcell::perception
