#include "app/common/build_identity.h"

#include "app/common/output_dir.h"
#include "assets/object_import.h"

namespace sortcell::app {

std::string BuildDigest() { return FileDigest("/proc/self/exe"); }

std::string FileDigest(const std::filesystem::path& file) { return assets::ContentDigest(ReadTextFile(file)); }

}  // namespace sortcell::app
