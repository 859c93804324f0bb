#pragma once
/// @file
/// The cell's bins and the rules that fill them, as the user writes them (scenes/cells/*.yaml):
///   name: kitchen
///   bins:
///     - {name: cans, at: [0.45, -0.50], size: [0.26, 0.26], colour: [0.45, 0.45, 0.48]}
///   rules: {bottle: bottles, can: cans, "*": others}
///   reject: others          # optional: where objects the model is unsure of go
///   reject_below: 0.05      # optional: below this calibrated confidence (0-1; 0: never; RecognitionModel::Result)
/// `at` is the centre of a bin's floor on the table (world x, y, m), `size` its inside (x, y, m);
/// walls are the cell's (cell::CellLayout). The simulated cell's bins are written from the same file
/// (BinsXml), so the robot's layout and the scene cannot disagree.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "cell/cell_layout.h"

namespace sortcell::files {

struct BinSpec {
  std::string name;
  cell::Bin bin;
  std::array<double, 3> colour{0.45, 0.45, 0.48};  ///< Its walls' RGB (0-1).
};

struct CellFile {
  std::string name;
  std::filesystem::path source;
  std::vector<BinSpec> bins;  ///< In the file's order.
  cell::SortingRules rules;

  /// The layout with these bins and rules (the rest as cell::CellLayout's defaults).
  cell::CellLayout Layout() const;
};

/// The default cell: scenes/cells/default.yaml under the data directory.
std::filesystem::path DefaultCellFile();

/// Reads and checks a cell file: bins that overlap, stand off the table or in the pick area, or
/// that the arm cannot reach into, and rules naming a bin that is not there are refused.
/// @throws std::invalid_argument "cell layout '<file>': <key or bin>: <what>".
CellFile ReadCellFile(const std::filesystem::path& file);

/// ReadCellFile(file), or of DefaultCellFile() when `file` is empty.
CellFile ReadCellFileOrDefault(const std::filesystem::path& file);

/// The bins as an MJCF fragment for the cell (models/cell/cell.inc.xml's classes and materials): a
/// body "bin_<name>" per bin, with a box site of that name at its floor centre sized to its inside,
/// walls as cell::CellLayout has them.
std::string BinsXml(const CellFile& cell);

}  // namespace sortcell::files
