// Cell layouts as data (scenes/cells/*.yaml): the default cell, a layout with a rule per category and a
// wildcard, the reject bin, the bins' MJCF written from the file, layouts refused with the reason, and
// `sortcell cell check` (unit).
#include "files/cell_file.h"

#include <gtest/gtest.h>

#include "files/output_dir.h"
#include "error_of.h"
#include "tests/app/run_sortcell.h"
#include "source_tree.h"
#include "temp_dir.h"

namespace sortcell::files {
namespace {

using sortcell_test::ErrorOf;

const std::filesystem::path kDefault =
    std::filesystem::path(sortcell_test::kSource) / "scenes" / "cells" / "default.yaml";

// A layout file in `dir` with `bins` (YAML list items) and `rest` (rules and the rest).
std::filesystem::path Layout(const sortcell_test::TempDir& dir, const std::string& bins, const std::string& rest) {
  const std::filesystem::path file = dir.path() / "layout.yaml";
  WriteTextFile(file, "name: test\nbins:\n" + bins + rest);
  return file;
}

const std::string kKitchenBins =
    "  - {name: bottles, at: [0.15, 0.50], size: [0.26, 0.26]}\n"
    "  - {name: cans, at: [0.45, 0.50], size: [0.20, 0.30]}\n"
    "  - {name: others, at: [0.30, -0.50], size: [0.30, 0.26]}\n";

TEST(CellFile, TheDefaultCellHasTodaysFourBinsSizedForTheBottlesAndAWildcard) {
  const CellFile cell = ReadCellFile(kDefault);
  ASSERT_EQ(cell.bins.size(), 4u);
  for (const auto& b : cell.bins) EXPECT_TRUE(b.bin.inner_half.isApprox(Eigen::Vector2d(0.13, 0.13))) << b.name;
  const cell::CellLayout layout = cell.Layout();
  for (const std::string c : {"bottle", "cup", "ball", "others"}) EXPECT_EQ(layout.rules.BinOf(c), c);
  EXPECT_EQ(layout.rules.BinOf("plate"), "others");  // "*"
  EXPECT_EQ(layout.rules.reject_bin, "others");
  EXPECT_EQ(layout.rules.reject_below, 0.0);
}

TEST(CellFile, TheDefaultBinsFragmentIsWrittenFromTheDefaultCell) {
  // scenes/cell.xml includes models/cell/bins.inc.xml: it must be what the cell file says
  // (`sortcell cell check scenes/cells/default.yaml --out DIR` writes it).
  const std::string committed =
      ReadTextFile(std::filesystem::path(sortcell_test::kSource) / "models/cell/bins.inc.xml");
  EXPECT_EQ(committed, BinsXml(ReadCellFile(kDefault)));
}

TEST(CellFile, ARulePerCategoryAWildcardAndARejectBin) {
  sortcell_test::TempDir dir;
  const auto file = Layout(dir, kKitchenBins,
                           "rules: {bottle: bottles, can: cans, \"*\": others}\nreject: others\nreject_below: 0.6\n");
  const cell::CellLayout layout = ReadCellFile(file).Layout();
  EXPECT_EQ(layout.rules.BinFor("bottle", 0.9), "bottles");
  EXPECT_EQ(layout.rules.BinFor("can", 0.9), "cans");
  EXPECT_EQ(layout.rules.BinFor("ball", 0.9), "others");    // The wildcard.
  EXPECT_EQ(layout.rules.BinFor("bottle", 0.5), "others");  // Unsure: the reject bin.
  EXPECT_TRUE(layout.bins.at("cans").inner_half.isApprox(Eigen::Vector2d(0.10, 0.15)));
  // Without a wildcard a category no rule names goes nowhere.
  const auto strict = Layout(dir, kKitchenBins, "rules: {bottle: bottles, can: cans}\n");
  EXPECT_FALSE(ReadCellFile(strict).rules.BinOf("ball").has_value());
}

TEST(CellFile, LayoutsTheRobotCannotWorkInAreRefusedWithTheReason) {
  sortcell_test::TempDir dir;
  const std::string rules = "rules: {\"*\": a}\n";
  const auto error = [&](const std::string& bins, const std::string& rest = "rules: {\"*\": a}\n") {
    const auto file = Layout(dir, bins, rest);
    const std::string e = ErrorOf([&] { ReadCellFile(file); });
    EXPECT_EQ(e.rfind("cell layout '" + file.string() + "': ", 0), 0u) << e;
    return e;
  };
  const std::string a = "  - {name: a, at: [0.15, 0.50], size: [0.26, 0.26]}\n";
  EXPECT_NE(error(a + "  - {name: b, at: [0.35, 0.50], size: [0.26, 0.26]}\n").find("bins 'a' and 'b' overlap"),
            std::string::npos);
  EXPECT_NE(error("  - {name: a, at: [0.5, 0.2], size: [0.2, 0.2]}\n").find("reaches into the pick area"),
            std::string::npos);
  EXPECT_NE(error("  - {name: a, at: [0.15, 0.68], size: [0.2, 0.2]}\n").find("stands off the table"),
            std::string::npos);
  EXPECT_NE(error("  - {name: a, at: [0.72, 0.55], size: [0.2, 0.2]}\n").find("the arm cannot reach down into it"),
            std::string::npos);
  EXPECT_NE(error("  - {name: a, at: [0.15, 0.5], size: [0.05, 0.2]}\n").find("expected 0.08-0.6 m a side"),
            std::string::npos);
  EXPECT_NE(error(a, "rules: {bottle: b}\n").find("rules: no bin 'b' in the layout"), std::string::npos);
  EXPECT_NE(error(a, rules + "reject_below: 0.5\n").find("needs a 'reject' bin"), std::string::npos);
  EXPECT_NE(error(a, rules + "colour: red\n").find("unknown key 'colour'"), std::string::npos);
  EXPECT_NE(error(a, "rules: {[x, y]: a}\n").find("key 'rules': expected category names"), std::string::npos);
  EXPECT_NE(error(a, "rules: {\"*\": \"\"}\n").find("key 'rules.*': expected a bin name"), std::string::npos);
  EXPECT_NE(error("  - {name: a, at: [0.15], size: [0.26, 0.26]}\n").find("bins[0].at': expected a list of 2 numbers"),
            std::string::npos);
}

TEST(CellCheckCli, SaysWhereEachCategoryGoesAndRefusesABadLayoutInOneLine) {
  sortcell_test::TempDir dir;
  const auto ok =
      sortcell_test::RunSortcell("cell check " + kDefault.string() + " --objects " + sortcell_test::kSource +
                                 "/scenes/objects/paper.yaml --out " + (dir.path() / "out").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("others       -> others"), std::string::npos) << ok.out;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / "scene.xml"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / "bins.inc.xml"));
  const auto bad = Layout(dir, "  - {name: a, at: [0.5, 0.2], size: [0.2, 0.2]}\n", "rules: {\"*\": a}\n");
  const auto r = sortcell_test::RunSortcell("cell check " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

}  // namespace
}  // namespace sortcell::files
