#include "app/cli/classify_command.h"

#include <algorithm>
#include <iostream>
#include <memory>

#include "perception/descriptor.h"
#include "perception/pcd_io.h"

namespace sortcell::app {
namespace {

struct ClassifyOptions {
  std::filesystem::path pcd, model;
  double reject_below = 0;
  int top = 3;
};

}  // namespace

nlohmann::json ClassifyObject(const perception::RecognitionModel& model, const perception::Cloud& object_C,
                              double reject_below, int top, const std::string& what) {
  const perception::Recognition recognition = perception::Recognise(object_C, model, reject_below);
  if (!recognition.described())
    throw std::invalid_argument(what + ": cannot be described (" + recognition.detail + ")");
  const perception::RecognitionModel::Result& result = recognition.result;
  nlohmann::json ranked = nlohmann::json::array();
  for (size_t k = 0; k < std::min<size_t>(std::max(top, 1), result.ranked.size()); ++k) {
    ranked.push_back({{"name", result.ranked[k].name}, {"probability", result.ranked[k].probability}});
  }
  return {{"category", recognition.category()},
          {"confidence", result.confidence},
          {"probability", result.probability},
          {"familiarity", result.familiarity},
          {"rejected", recognition.rejected},
          {"points", object_C.size()},
          {"top", ranked}};
}

void AddClassifyCommand(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<ClassifyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "classify",
      "Name the category of one segmented object cloud (a segment_NN.pcd from sortcell segment, or any "
      "object's points in the camera frame; organized or not) with a model from sortcell train: the "
      "category, its confidence (the SVM's probability) and the runners-up. JSON on stdout. With "
      "--reject-below P, an object whose confidence is below P is called 'unknown'.");
  cmd->add_option("--pcd", o->pcd, "The object's cloud (PCD with x y z rgb/rgba, camera frame)")->required();
  cmd->add_option("--model", o->model, "Model file from sortcell train")->required();
  cmd->add_option("--reject-below", o->reject_below, "Call the object 'unknown' below this confidence (0-1)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--top", o->top, "How many classes to list, most probable first")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->callback([&run, o] {
    run = [o] {
      const perception::RecognitionModel model = perception::LoadModel(o->model);
      const perception::Cloud::Ptr cloud = perception::LoadCloud(o->pcd, /*organized=*/false);
      nlohmann::json result = ClassifyObject(model, *cloud, o->reject_below, o->top, "PCD '" + o->pcd.string() + "'");
      result["pcd"] = o->pcd.string();
      result["model"] = o->model.string();
      result["descriptor"] = perception::DescriptorName(model.descriptor);
      std::cout << result.dump(2) << "\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
