// model_spec.hpp - a head-pose model's description file (estimator/models/NAME.model):
// input size, colour order, normalisation, decoder kind and its outputs. Another
// ONNX head-pose model plugs in with a new file wherever its decoder exists.
#pragma once

#include <array>
#include <stdexcept>
#include <string>

namespace hkf_estimator {

struct EstimatorError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Where a missing model comes from, for both a source tree and an installed one.
inline const std::string kModelsHint =
    "in a source tree scripts/setup.sh fetches and converts the models; an installed hkf has them in "
    "share/hkf/models beside its bin/, or give --models-dir DIR or HKF_MODELS_DIR";

struct AngleBins {
    std::string output;  // the network output holding this angle's logits
    int bins = 0;
    float step = 0.f;    // deg per bin
    float offset = 0.f;  // deg of bin 0
};

struct ModelSpec {
    std::string name;        // from the file name
    std::string file;        // the ONNX file, absolute
    int input_width = 0, input_height = 0;
    bool rgb = true;         // false: BGR
    float scale = 1.f;
    std::array<float, 3> mean{0.f, 0.f, 0.f}, std{1.f, 1.f, 1.f};
    std::string decoder;     // "angle_bins" or "landmarks_pnp"
    // angle_bins: the three heads
    AngleBins yaw, pitch, roll;
    // landmarks_pnp: the mesh output (x y z per landmark, input px), its face
    // flag, the canonical 3D face (x y z per line), the region and the camera
    std::string landmarks_output, flag_output, canonical;
    int landmarks = 0;
    float roi_scale = 1.5f;        // the region: the detection box's long side times this
    float roi_face_cm = 0.f;       // a followed face's region: this many cm of face at its front; 0: the box's
    float min_face_flag = 0.5f;    // below: no face in the region
    float focal_scale = 1.0f;      // focal length in px = this * the frame's long side
    std::array<float, 3> signs{1.f, 1.f, 1.f};  // model -> hkf convention, pitch yaw roll
    float crop_margin = 0.2f;
    // angle_bins, tried by dev/eval/crop_variants.py (off unless a description turns them on):
    bool flip_average = false;     // also the mirrored crop, its yaw and roll negated; the two averaged
    float profile_from_deg = 0.f;  // where the first reading's |yaw| is at least this (0: never), read again
    float profile_margin = 0.2f;   //   from a crop with this margin
    float profile_shift = 0.f;     //   moved by this share of the box's width toward the yaw's sign
};

// Reads SPEC_DIR/NAME.model; the model file is looked up in MODELS_DIR.
// Throws EstimatorError naming the file and line at fault.
ModelSpec load_model_spec(const std::string &spec_dir, const std::string &name, const std::string &models_dir);

}  // namespace hkf_estimator
