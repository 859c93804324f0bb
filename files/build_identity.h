#pragma once
/// @file
/// Digests that tell builds and files apart, for records that must be reproduced exactly (a sweep's
/// episodes, replayed by `sortcell replay`).

#include <filesystem>
#include <string>

namespace sortcell::files {

/// A digest of this executable's bytes (/proc/self/exe): two builds of different code differ.
/// @throws std::runtime_error "cannot read '/proc/self/exe'".
std::string BuildDigest();

/// A digest of a file's bytes.
/// @throws std::runtime_error "cannot read '<file>'".
std::string FileDigest(const std::filesystem::path& file);

}  // namespace sortcell::files
