#include "files/build_identity.h"

#include "files/output_dir.h"
#include "assets/object_import.h"

namespace sortcell::files {

std::string BuildDigest() { return FileDigest("/proc/self/exe"); }

std::string FileDigest(const std::filesystem::path& file) { return assets::ContentDigest(ReadTextFile(file)); }

}  // namespace sortcell::files
