#pragma once
// Where the tests find the project's files: the source tree (SORTCELL_SOURCE_DIR, set for every test
// by tests/CMakeLists.txt) and the default cell scene.
#include <filesystem>
#include <string>

namespace sortcell_test {

/// The source tree's root, to join paths to.
inline const std::filesystem::path kRoot = SORTCELL_SOURCE_DIR;
/// The same as a string, to append to.
inline const std::string kSource = SORTCELL_SOURCE_DIR;
/// The default cell (scenes/cell.xml).
inline const std::string kCell = kSource + "/scenes/cell.xml";

}  // namespace sortcell_test
