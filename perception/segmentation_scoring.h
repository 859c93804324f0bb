#pragma once
/// @file
/// Scores segments against ground truth per pixel (the label image in simulation, a labelled real
/// capture): how many objects came out as one segment, merged with others, split or missed, and the
/// overlap precision, recall and F-measure of predicted against true object pixels under a one-to-one
/// matching of segments to objects.

#include <vector>

namespace sortcell::perception {

struct SegmentationScore {
  int objects = 0;   ///< True objects (with at least the minimum of pixels).
  int segments = 0;  ///< Predicted segments.
  /// Each object is exactly one of: found (IoU >= 0.5 with the segment matched to it one to one); merged
  /// (not found, but one segment holds at least half of it: a segment that is as much something else);
  /// split (no segment holds half of it, segments together hold half or more); missed (the rest).
  int found = 0, merged = 0, split = 0, missed = 0;
  /// Pixels: of the true objects, of the segments, and shared by matched pairs (segments matched one to
  /// one to objects, largest IoU first). Pooled over frames by adding them up.
  long true_pixels = 0, predicted_pixels = 0, matched_pixels = 0;
  double OverlapPrecision() const {
    return predicted_pixels > 0 ? static_cast<double>(matched_pixels) / predicted_pixels : 0;
  }
  double OverlapRecall() const { return true_pixels > 0 ? static_cast<double>(matched_pixels) / true_pixels : 0; }
  double OverlapF() const;
  double FoundRate() const { return objects > 0 ? static_cast<double>(found) / objects : 0; }
};

/// `truth`: an object id per pixel of the frame (0 = not an object: nothing, the table, the floor);
/// `segments`: each segment's pixel indices into the same frame. Objects with fewer than
/// `min_object_pixels` pixels are not counted: their pixels are not true object pixels, and a segment's
/// pixels on them count as predicted pixels that match nothing.
/// @throws std::invalid_argument if a segment's pixel index lies outside the frame.
SegmentationScore ScoreSegmentation(const std::vector<int>& truth, const std::vector<std::vector<int>>& segments,
                                    int min_object_pixels = 1);

/// The sum of several frames' scores (counts and pixels added).
SegmentationScore PoolScores(const std::vector<SegmentationScore>& scores);

}  // namespace sortcell::perception
