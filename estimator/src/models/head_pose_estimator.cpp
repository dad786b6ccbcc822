// head_pose_estimator.cpp - see head_pose_estimator.hpp.
#include "head_pose_estimator.hpp"

#include "angle_bins_model.hpp"
#include "mesh_pnp_model.hpp"

namespace hkf_estimator {

std::unique_ptr<HeadPoseEstimator> make_estimator(const ModelSpec &spec)
{
    if (spec.decoder == "angle_bins") return std::make_unique<AngleBinsModel>(spec);
    if (spec.decoder == "landmarks_pnp") return std::make_unique<MeshPnpModel>(spec);
    throw EstimatorError("no estimator for decoder '" + spec.decoder + "'");
}

}  // namespace hkf_estimator
