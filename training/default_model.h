#pragma once
/// @file
/// The cached recognition model an episode uses when none is named: Color-CVFH (normalization)
/// trained on random cell scenes of the object set (the conditions the sorting cell sees), kept in
/// the model cache folder (ModelCacheDir: the build folder's models/ by default, never the source tree).

#include <filesystem>
#include <string>

#include "files/object_set.h"
#include "perception/recognition_model.h"

namespace sortcell::training {

/// The default recipe's count of random cell scenes of a set's own objects (TrainDefaultRecipe); every
/// cached default model is trained with it.
inline constexpr int kDefaultRecipeScenes = 150;

/// The folder of cached default models: $SORTCELL_MODEL_CACHE when set; else the folder the build
/// names (compile definition SORTCELL_DEFAULT_MODEL_CACHE, <build folder>/models); else out/models
/// under the working directory.
std::filesystem::path ModelCacheDir();

/// <ModelCacheDir()>/<set name>-color-cvfh-norm.model.json.
std::filesystem::path DefaultModelPath(const files::ObjectSet& set);

/// The command that makes the default model, for error messages.
std::string DefaultModelHint(const files::ObjectSet& set);

/// Whether the cached default model of `set` exists and was trained on the set's current object models
/// and the current Kinect colour model (the digest beside it says so; a model without one was put there
/// by hand, with sortcell train, and counts as current).
bool DefaultModelIsCurrent(const files::ObjectSet& set);
/// Whether `model` exists and its digest (<model>.trained_on, RecordTrainedOn) says it was made by the
/// default recipe from `set`'s current objects through the current sensor models (false without one).
/// `scenes`: the recipe's count of scenes of the set's own objects the model was trained with.
bool TrainedOnIsCurrent(const files::ObjectSet& set, const std::filesystem::path& model,
                        int scenes = kDefaultRecipeScenes);
/// Removes <model>.trained_on if there is one (a model written by other means is not the recipe's).
/// @throws std::runtime_error if it cannot.
void ForgetTrainedOn(const std::filesystem::path& model);

/// The default recipe, the one every default model is made with: random cell scenes of `set` (`scenes`,
/// 150 unless `sortcell train --scenes` says otherwise: fewer for a quick model; seed
/// 0; sparse, dense and clustered in turns; 30 % of the bottles and boxes lying), its training variety
/// among its own objects (as many scenes per object, in groups of at most 60 objects: MuJoCo 2.2 draws at
/// most 100 textures in one scene), and for each group a twin of other scenes through a widened sensor
/// (colours jittered, depth noisier) that trains the classifier but not the familiarity; captured into
/// `dataset_dir` (kept there), and Color-CVFH (normalization) trained on them all.
/// @throws std::invalid_argument if `scenes` < 1.
perception::RecognitionModel TrainDefaultRecipe(const files::ObjectSet& set, const std::filesystem::path& dataset_dir,
                                                int scenes = kDefaultRecipeScenes);

/// The recipe in words, e.g. "150 random cell scenes, more in proportion for a training variety
/// (sparse,dense,clustered; 30 % lying; ...; seed 0), and as many other scenes through a widened sensor
/// for the classifier only (...), Color-CVFH (normalization)".
std::string DefaultRecipeTitle(int scenes_count = kDefaultRecipeScenes);

/// Writes beside `model` (<model>.trained_on) what a model of `set` made with TrainDefaultRecipe was
/// trained on, so that the model cache takes it as current. @throws std::runtime_error if it cannot.
void RecordTrainedOn(const files::ObjectSet& set, const std::filesystem::path& model,
                     int scenes = kDefaultRecipeScenes);

/// Trains the default model of `set` if it is not there yet, or was trained on other objects, another
/// Kinect colour or depth model or another recipe (TrainDefaultRecipe; about 45 s for the paper set on 2 cores;
/// the scenes' dataset is kept next to it) and returns its path. Written to a temporary file and
/// renamed, so concurrent runs never read a half-written model.
std::filesystem::path EnsureDefaultModel(const files::ObjectSet& set);

}  // namespace sortcell::training
