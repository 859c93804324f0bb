#include "sim/point_cloud.h"

#include <cmath>
#include <limits>

namespace sortcell::sim {

pcl::PointCloud<pcl::PointXYZRGB>::Ptr ToOrganizedCloud(const KinectFrame& frame) {
  const CameraIntrinsics& k = frame.intrinsics;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZRGB>>(k.width, k.height);
  cloud->is_dense = false;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < k.height; ++v) {
    const float* z = frame.depth.ptr<float>(v);
    const cv::Vec3b* rgb = frame.rgb.ptr<cv::Vec3b>(v);
    for (int u = 0; u < k.width; ++u) {
      pcl::PointXYZRGB& p = cloud->at(u, v);
      p.r = rgb[u][0];
      p.g = rgb[u][1];
      p.b = rgb[u][2];
      if (std::isfinite(z[u])) {
        p.x = static_cast<float>((u - k.cx) * z[u] / k.fx);
        p.y = static_cast<float>((v - k.cy) * z[u] / k.fy);
        p.z = z[u];
      } else {
        p.x = p.y = p.z = nan;
      }
    }
  }
  return cloud;
}

}  // namespace sortcell::sim
