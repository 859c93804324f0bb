#include "sim/kinect_camera.h"

#include <chrono>
#include <stdexcept>
#include <utility>

namespace sortcell::sim {

KinectCamera::KinectCamera(const Model& model, const std::string& camera_name, int width, int height)
    : model_(model),
      camera_id_(model.Id(mjOBJ_CAMERA, camera_name)),
      intrinsics_(IntrinsicsOf(model, camera_id_, width, height)),
      renderer_(model),
      object_names_(FreeBodyNames(model)) {
  renderer_.CheckViewSize(width, height);
  // Objects are the free bodies; every geom in an object's subtree carries its label.
  std::vector<uint16_t> body_label(model->nbody, 0);
  for (size_t i = 0; i < object_names_.size(); ++i) {
    body_label[model.Id(mjOBJ_BODY, object_names_[i])] = static_cast<uint16_t>(i + 1);
  }
  geom_label_.assign(model->ngeom, 0);
  for (int g = 0; g < model->ngeom; ++g) {
    int b = model->geom_bodyid[g];
    while (b > 0 && body_label[b] == 0) b = model->body_parentid[b];
    geom_label_[g] = body_label[b];
  }
}

KinectFrame KinectCamera::Capture(const Data& data, const KinectNoiseParams* noise, std::mt19937_64* rng,
                                  FrameTruth* truth) {
  if (noise != nullptr && rng == nullptr) throw std::invalid_argument("KinectCamera::Capture: noise needs an rng");
  KinectFrame frame = RenderClean(data, truth);
  if (noise == nullptr) return frame;
  const auto start = std::chrono::steady_clock::now();
  frame = ApplySensorModel(std::move(frame), *noise, *rng);
  timings_.noise_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

KinectFrame KinectCamera::RenderClean(const Data& data, FrameTruth* truth) {
  const RenderView view{camera_id_, intrinsics_.width, intrinsics_.height};
  KinectFrame frame;
  frame.intrinsics = intrinsics_;
  auto start = std::chrono::steady_clock::now();
  const auto lap = [&start](double& total) {
    const auto now = std::chrono::steady_clock::now();
    total += std::chrono::duration<double>(now - start).count();
    start = now;
  };
  cv::Mat depth_buffer;
  renderer_.Render(data, view, frame.rgb, depth_buffer);
  frame.depth = LinearizeDepth(depth_buffer, DepthRangeOf(model_));
  lap(timings_.render_s);
  if (truth == nullptr) return frame;

  truth->X_WC = CameraPoseInWorld(model_, data, camera_id_);
  cv::Mat geom_ids;
  renderer_.RenderGeomIds(data, view, geom_ids);
  truth->labels.create(geom_ids.size(), CV_16UC1);
  for (int r = 0; r < geom_ids.rows; ++r) {
    const int* g = geom_ids.ptr<int>(r);
    uint16_t* l = truth->labels.ptr<uint16_t>(r);
    for (int c = 0; c < geom_ids.cols; ++c) l[c] = g[c] >= 0 ? geom_label_[g[c]] : 0;
  }
  lap(timings_.labels_s);
  return frame;
}

KinectFrame KinectCamera::ApplySensorModel(KinectFrame clean, const KinectNoiseParams& noise, std::mt19937_64& rng) {
  // The depth's draws first, then the colour's, as the sensor model has always drawn them.
  clean.depth = ApplyKinectNoise(clean.depth, clean.intrinsics, noise, rng);
  clean.rgb = ApplyKinectColour(clean.rgb, noise.colour, rng);
  return clean;
}

}  // namespace sortcell::sim
