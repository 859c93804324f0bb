#pragma once
/// @file
/// The RGB-D Object Dataset (Lai et al., ICRA 2011) read as it is published, into a SortCell dataset:
/// per view `<instance>_<video>_<frame>_crop.png` (8-bit colour crop around the object),
/// `_depthcrop.png` (16-bit, millimetres, 0 = no depth), `_maskcrop.png` (the object's pixels) and
/// `_loc.txt` ("X,Y": the crop's top-left pixel in the 640x480 frame, 1-based), in
/// `<category>/<instance>/` folders. Each view's masked pixels with depth are back-projected with the
/// dataset's Kinect intrinsics into a camera-frame cloud and described like a simulated capture, so
/// train, eval and the experiments run on it unchanged.

#include <filesystem>
#include <string>
#include <vector>

#include "training/dataset.h"
#include "perception/cloud.h"

namespace sortcell::training {

/// The dataset's Kinect: fx = fy = 570.3 px, principal point (320, 240) in the 640x480 frame.
struct RgbdObjectsCamera {
  double focal_px = 570.3;
  double cx = 320, cy = 240;
  /// The dataset's masks reach a few pixels past the object's depth edges (DESIGN.md section 5): a
  /// masked pixel whose 3x3 neighbourhood in the depth crop spans more than `edge_jump_m` is at a
  /// depth edge (a mixed pixel, or background beside the object), and one farther than
  /// `from_median_m` from the masked pixels' median depth is background seen past the object; both
  /// are left out, and of what remains only the largest connected region is kept (the masks also
  /// cover patches of the table beside the object, nearer than `from_median_m` behind it: a real ball's
  /// cloud reached 0.15 m deep with them, 0.03 m without).
  double edge_jump_m = 0.02;
  double from_median_m = 0.15;
};

/// One view: its colour crop and where it belongs.
struct RgbdObjectsView {
  std::filesystem::path crop;  ///< `<instance>_<video>_<frame>_crop.png`; the partners share its stem.
  std::string category;        ///< The folder above the instance's folder (else the instance less `_<n>`).
  std::string instance;        ///< From the file name.
  int video = 0, frame = 0;
};

/// Every `*_crop.png` view under `root` (recursively), sorted by path.
/// @throws std::invalid_argument "RGB-D Object Dataset folder '<root>': <what>" if it is not a folder.
std::vector<RgbdObjectsView> FindRgbdObjectsViews(const std::filesystem::path& root);

/// A view's partner file: `suffix` "depthcrop.png", "maskcrop.png" or "loc.txt" in place of "crop.png".
std::filesystem::path Partner(const RgbdObjectsView& view, const std::string& suffix);

/// One view's masked pixels with depth as a camera-frame cloud (m; optical frame, z forward),
/// unorganized, coloured from the crop; pixels at depth edges or far from the object's median depth
/// left out (RgbdObjectsCamera).
/// @throws std::invalid_argument naming the file: a partner file missing or unreadable, images of
///         different sizes, a loc file that is not "X,Y" with the crop inside the 640x480 frame.
perception::Cloud::Ptr ReadRgbdObjectsView(const RgbdObjectsView& view, const RgbdObjectsCamera& camera = {});

/// Reads and describes every view under `root` and writes the clouds into `dir`/clouds (the caller
/// saves the manifest with SaveDataset). A view that cannot be read or described is skipped, and
/// named with the reason in capture["skipped"]. The videos of an instance, lowest number first, are
/// its 30, 45 and 60 degree sequences (the dataset's three camera heights): elevation_deg tells them
/// apart; frame is the frame number.
/// @throws std::invalid_argument if `root` holds no view at all.
Dataset ImportRgbdObjects(const std::filesystem::path& root, const std::filesystem::path& dir,
                          const RgbdObjectsCamera& camera = {});

}  // namespace sortcell::training
