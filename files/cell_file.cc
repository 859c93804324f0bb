#include "files/cell_file.h"

#include <set>
#include <sstream>
#include <stdexcept>

#include "files/data_dir.h"
#include "files/yaml_reader.h"
#include "cell/layout_check.h"
#include "sim/ground_truth.h"

namespace sortcell::files {
namespace {

constexpr double kFloorThickness = 0.008;  // The bins' floor plate (m); its top is the floor site.

// A list of `n` numbers at `key` of `node`.
std::vector<double> Numbers(const YamlReader& reader, const YAML::Node& node, const std::string& key, size_t n,
                            const std::string& where) {
  const YAML::Node list = node[key];
  const std::string name = where + "." + key;
  if (!list) reader.Fail("missing key '" + name + "'");
  if (!list.IsSequence() || list.size() != n) {
    reader.Fail("key '" + name + "': expected a list of " + std::to_string(n) + " numbers, found " + NodeKind(list));
  }
  std::vector<double> values;
  for (size_t i = 0; i < n; ++i) values.push_back(reader.Number(list[i], name));
  return values;
}

BinSpec ReadBin(const YamlReader& reader, const YAML::Node& node, const std::string& where) {
  if (!node.IsMap()) reader.Fail("key '" + where + "': expected a map, found " + NodeKind(node));
  reader.RejectUnknownKeys(node, where, {"name", "at", "size", "colour"});
  BinSpec spec;
  spec.name = reader.String(node, "name", where);
  for (const char c : spec.name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') {
      reader.Fail("key '" + where + ".name': expected letters, digits, '_' or '-', found '" + spec.name + "'");
    }
  }
  const std::vector<double> at = Numbers(reader, node, "at", 2, where);
  const std::vector<double> size = Numbers(reader, node, "size", 2, where);
  spec.bin.p_W_floor = Eigen::Vector3d(at[0], at[1], kFloorThickness);
  spec.bin.inner_half = 0.5 * Eigen::Vector2d(size[0], size[1]);
  if (node["colour"]) {
    const std::vector<double> rgb = Numbers(reader, node, "colour", 3, where);
    for (int i = 0; i < 3; ++i) {
      if (!(rgb[i] >= 0 && rgb[i] <= 1)) reader.Fail("key '" + where + ".colour': expected values in [0, 1]");
      spec.colour[i] = rgb[i];
    }
  }
  return spec;
}

cell::SortingRules ReadRules(const YamlReader& reader, const YAML::Node& root) {
  cell::SortingRules rules;
  const YAML::Node map = root["rules"];
  if (!map) reader.Fail("missing key 'rules'");
  if (!map.IsMap() || map.size() == 0) reader.Fail("key 'rules': expected a map category: bin, found " + NodeKind(map));
  for (const auto& rule : map) {
    if (!rule.first.IsScalar() || rule.first.Scalar().empty()) {
      reader.Fail("key 'rules': expected category names (or \"*\") as keys, found " + NodeKind(rule.first));
    }
    const std::string category = rule.first.Scalar();
    if (!rule.second.IsScalar() || rule.second.Scalar().empty()) {
      reader.Fail("key 'rules." + category + "': expected a bin name, found " + NodeKind(rule.second));
    }
    const std::string bin = rule.second.Scalar();
    (category == "*" ? rules.otherwise : rules.bin_of[category]) = bin;
  }
  if (root["reject"]) rules.reject_bin = reader.String(root, "reject", "the top level");
  if (root["reject_below"]) {
    rules.reject_below = reader.Number(root["reject_below"], "reject_below");
    if (!(rules.reject_below >= 0 && rules.reject_below <= 1)) reader.Fail("key 'reject_below': expected 0-1");
    if (rules.reject_below > 0 && rules.reject_bin.empty()) reader.Fail("key 'reject_below': needs a 'reject' bin");
  }
  return rules;
}

}  // namespace

cell::CellLayout CellFile::Layout() const {
  cell::CellLayout layout;
  for (const auto& spec : bins) layout.bins[spec.name] = spec.bin;
  layout.rules = rules;
  return layout;
}

std::filesystem::path DefaultCellFile() {
  return std::filesystem::path(DataDir()) / "scenes" / "cells" / "default.yaml";
}

CellFile ReadCellFile(const std::filesystem::path& file) {
  const YamlReader reader("cell layout", file);
  const YAML::Node root = reader.LoadMap("name, bins and rules");
  reader.RejectUnknownKeys(root, "the top level", {"name", "bins", "rules", "reject", "reject_below"});
  CellFile cell;
  cell.source = file;
  cell.name = reader.String(root, "name", "the top level");
  const YAML::Node bins = root["bins"];
  if (!bins) reader.Fail("missing key 'bins'");
  if (!bins.IsSequence() || bins.size() == 0)
    reader.Fail("key 'bins': expected a non-empty list, found " + NodeKind(bins));
  std::set<std::string> names;
  for (size_t i = 0; i < bins.size(); ++i) {
    BinSpec spec = ReadBin(reader, bins[i], "bins[" + std::to_string(i) + "]");
    if (!names.insert(spec.name).second) reader.Fail("duplicate bin name '" + spec.name + "'");
    cell.bins.push_back(std::move(spec));
  }
  cell.rules = ReadRules(reader, root);
  const cell::CellLayout layout = cell.Layout();
  try {
    cell::CheckBins(layout);
    cell::CheckRules(layout, {});
  } catch (const std::invalid_argument& e) {
    reader.Fail(e.what());
  }
  return cell;
}

CellFile ReadCellFileOrDefault(const std::filesystem::path& file) {
  return ReadCellFile(file.empty() ? DefaultCellFile() : file);
}

std::string BinsXml(const CellFile& cell) {
  const cell::CellLayout walls = cell.Layout();
  std::ostringstream xml;
  xml.precision(6);
  xml << "<!-- The bins of cell layout '" << cell.name << "' (written by sortcell from "
      << cell.source.filename().string() << "). -->\n<mujoco>\n  <asset>\n";
  for (const auto& b : cell.bins) {
    xml << "    <material name=\"" << sim::BinName(b.name) << "\" rgba=\"" << b.colour[0] << " " << b.colour[1] << " "
        << b.colour[2] << " 1\"/>\n";
  }
  xml << "  </asset>\n  <worldbody>\n";
  const double t = walls.bin_wall_thickness, h = walls.bin_wall_height;
  for (const auto& b : cell.bins) {
    const Eigen::Vector2d in = b.bin.inner_half, out = in.array() + t;
    const std::string name = sim::BinName(b.name);
    xml << "    <body name=\"" << name << "\" pos=\"" << b.bin.p_W_floor.x() << " " << b.bin.p_W_floor.y()
        << " 0\" childclass=\"env\">\n";
    xml << "      <site name=\"" << name << "\" type=\"box\" pos=\"0 0 " << kFloorThickness << "\" size=\"" << in.x()
        << " " << in.y() << " 0.001\" group=\"4\"/>\n";
    xml << "      <geom type=\"box\" pos=\"0 0 " << kFloorThickness / 2 << "\" size=\"" << out.x() << " " << out.y()
        << " " << kFloorThickness / 2 << "\" material=\"bins_floor\"/>\n";
    const double wall_z = kFloorThickness + (h - kFloorThickness) / 2, wall_half = (h - kFloorThickness) / 2;
    for (const double s : {1.0, -1.0}) {
      xml << "      <geom type=\"box\" pos=\"" << s * (in.x() + t / 2) << " 0 " << wall_z << "\" size=\"" << t / 2
          << " " << out.y() << " " << wall_half << "\" material=\"" << name << "\"/>\n";
    }
    for (const double s : {1.0, -1.0}) {
      xml << "      <geom type=\"box\" pos=\"0 " << s * (in.y() + t / 2) << " " << wall_z << "\" size=\"" << in.x()
          << " " << t / 2 << " " << wall_half << "\" material=\"" << name << "\"/>\n";
    }
    xml << "    </body>\n";
  }
  xml << "  </worldbody>\n</mujoco>\n";
  return xml.str();
}

}  // namespace sortcell::files
