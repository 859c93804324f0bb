#pragma once
/// @file
/// Where the repository's models/ and scenes/ live at run time.

#include <string>

namespace sortcell::app {

/// $SORTCELL_DATA_DIR, else the source tree this binary was built from.
std::string DataDir();

}  // namespace sortcell::app
