// Fuzz target: a recognition model file (perception::LoadModel), then one classification with it so
// that a model that loads is a model that can be used.
#include "fuzz/fuzz_input.h"
#include "perception/recognition_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "input.model.json";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] {
    const sortcell::perception::RecognitionModel model = sortcell::perception::LoadModel(file);
    sortcell::perception::DescriptorParts parts;
    parts.hsv = Eigen::VectorXf::Ones(192);
    parts.cvfh = Eigen::VectorXf::Ones(308);
    model.Classify(parts);
  });
  return 0;
}
