#include "perception/segmentation_scoring.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace sortcell::perception {

double SegmentationScore::OverlapF() const {
  const double p = OverlapPrecision(), r = OverlapRecall();
  return p + r > 0 ? 2 * p * r / (p + r) : 0;
}

namespace {

// Pixels shared by each (segment, object) pair, and each object's and segment's size.
struct Overlaps {
  std::map<int, long> object_size;
  std::vector<long> segment_size;
  std::map<std::pair<int, int>, long> shared;  // (segment, object) -> pixels.
};

Overlaps Count(const std::vector<int>& truth, const std::vector<std::vector<int>>& segments,
               const std::map<int, long>& objects) {
  Overlaps o;
  o.object_size = objects;
  for (size_t s = 0; s < segments.size(); ++s) {
    o.segment_size.push_back(static_cast<long>(segments[s].size()));
    for (int pixel : segments[s]) {
      if (pixel < 0 || pixel >= static_cast<int>(truth.size())) {
        throw std::invalid_argument("segmentation scoring: segment " + std::to_string(s) + " has pixel " +
                                    std::to_string(pixel) + " outside the frame's " + std::to_string(truth.size()));
      }
      if (objects.count(truth[pixel])) ++o.shared[{static_cast<int>(s), truth[pixel]}];
    }
  }
  return o;
}

double Iou(long shared, long a, long b) { return static_cast<double>(shared) / static_cast<double>(a + b - shared); }

}  // namespace

SegmentationScore ScoreSegmentation(const std::vector<int>& truth, const std::vector<std::vector<int>>& segments,
                                    int min_object_pixels) {
  std::map<int, long> all;
  for (int id : truth) {
    if (id != 0) ++all[id];
  }
  std::map<int, long> objects;
  for (const auto& [id, size] : all) {
    if (size >= min_object_pixels) objects[id] = size;
  }
  const Overlaps o = Count(truth, segments, objects);
  SegmentationScore score;
  score.objects = static_cast<int>(objects.size());
  score.segments = static_cast<int>(segments.size());
  for (const auto& [id, size] : objects) score.true_pixels += size;
  for (long size : o.segment_size) score.predicted_pixels += size;

  // One-to-one matching, largest IoU first.
  std::vector<std::tuple<double, int, int>> pairs;  // (IoU, segment, object)
  for (const auto& [key, shared] : o.shared) {
    pairs.emplace_back(Iou(shared, o.segment_size[key.first], objects.at(key.second)), key.first, key.second);
  }
  // Largest IoU first; ties by segment, then object (a fixed order, so equal IoUs always match alike).
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    return std::get<0>(a) != std::get<0>(b)
               ? std::get<0>(a) > std::get<0>(b)
               : std::tie(std::get<1>(a), std::get<2>(a)) < std::tie(std::get<1>(b), std::get<2>(b));
  });
  std::vector<bool> segment_used(segments.size(), false);
  std::map<int, double> matched_iou;  // Object -> the IoU of its one-to-one match.
  for (const auto& [iou, s, id] : pairs) {
    if (segment_used[s] || matched_iou.count(id)) continue;
    segment_used[s] = true;
    matched_iou[id] = iou;
    score.matched_pixels += o.shared.at({s, id});
  }

  for (const auto& [id, size] : objects) {
    long most = 0, covered = 0;
    for (size_t s = 0; s < segments.size(); ++s) {
      const auto it = o.shared.find({static_cast<int>(s), id});
      if (it == o.shared.end()) continue;
      covered += it->second;
      most = std::max(most, it->second);
    }
    const auto match = matched_iou.find(id);
    if (match != matched_iou.end() && match->second >= 0.5) {
      ++score.found;
    } else if (2 * most >= size) {
      ++score.merged;
    } else if (2 * covered >= size) {
      ++score.split;
    } else {
      ++score.missed;
    }
  }
  return score;
}

SegmentationScore PoolScores(const std::vector<SegmentationScore>& scores) {
  SegmentationScore total;
  for (const auto& s : scores) {
    total.objects += s.objects;
    total.segments += s.segments;
    total.found += s.found;
    total.merged += s.merged;
    total.split += s.split;
    total.missed += s.missed;
    total.true_pixels += s.true_pixels;
    total.predicted_pixels += s.predicted_pixels;
    total.matched_pixels += s.matched_pixels;
  }
  return total;
}

}  // namespace sortcell::perception
