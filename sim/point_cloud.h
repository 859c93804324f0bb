#pragma once
/// @file
/// The organized point cloud a Kinect driver delivers, from a synthetic capture.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "sim/kinect_camera.h"

namespace sortcell::sim {

/// Organized width x height cloud in the camera's optical frame (x right, y down, z forward),
/// one point per pixel (row-major, index = row * width + col), NaN coordinates where depth is
/// invalid, colour from the registered RGB image. is_dense = false; the sensor origin is identity.
pcl::PointCloud<pcl::PointXYZRGB>::Ptr ToOrganizedCloud(const KinectFrame& frame);

}  // namespace sortcell::sim
