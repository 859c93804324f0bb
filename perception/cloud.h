#pragma once
/// @file
/// The point type every perception stage works on: a Kinect point with registered colour.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace sortcell::perception {

using PointT = pcl::PointXYZRGB;
using Cloud = pcl::PointCloud<PointT>;

}  // namespace sortcell::perception
