// mesh_pnp_model.cpp - see mesh_pnp_model.hpp.
#include "mesh_pnp_model.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "head_rotation.hpp"
#include "network_outputs.hpp"
#include "onnx_network.hpp"

namespace hkf_estimator {

namespace {

// The canonical face's frame (x to the subject's left, y up, z towards the
// camera) turned into camera coordinates for a face looking into the camera.
const cv::Matx33d kCanonicalToCamera(1, 0, 0, 0, -1, 0, 0, 0, -1);

std::vector<cv::Point3f> read_canonical(const std::string &path, int count)
{
    std::ifstream in(path);
    if (!in) throw EstimatorError("canonical face " + path + " is missing (" + kModelsHint + ")");
    std::vector<cv::Point3f> points;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        cv::Point3f p;
        if (!(fields >> p.x >> p.y >> p.z)) throw EstimatorError(path + ": a line is not 'x y z'");
        points.push_back(p);
    }
    if (static_cast<int>(points.size()) != count)
        throw EstimatorError(path + " has " + std::to_string(points.size()) + " points, the mesh gives " + std::to_string(count));
    return points;
}

}  // namespace

MeshPnpModel::MeshPnpModel(ModelSpec spec) : spec_(std::move(spec))
{
    net_ = load_onnx_network(spec_.file, {spec_.landmarks_output, spec_.flag_output});
    canonical_ = read_canonical(spec_.canonical, spec_.landmarks);
    rigid_ = rigid_points(canonical_);
    for (int i : rigid_) rigid_canonical_.push_back(canonical_[static_cast<size_t>(i)]);
    for (const cv::Point3f &p : canonical_) front_z_ = std::max(front_z_, p.z);
}

bool MeshPnpModel::landmarks_in_region(const cv::Mat &frame, const cv::Point2f &centre, double angle, float side)
{
    cv::Mat to_input = cv::getRotationMatrix2D(centre, angle, spec_.input_width / side);
    to_input.at<double>(0, 2) += spec_.input_width / 2.0 - centre.x;
    to_input.at<double>(1, 2) += spec_.input_height / 2.0 - centre.y;
    cv::Mat patch;
    cv::warpAffine(frame, patch, to_input, cv::Size(spec_.input_width, spec_.input_height), cv::INTER_LINEAR,
                   cv::BORDER_CONSTANT);

    net_.setInput(network_input(spec_, patch));
    std::vector<cv::Mat> out;
    net_.forward(out, std::vector<std::string>{spec_.landmarks_output, spec_.flag_output});
    if (out.size() != 2) throw EstimatorError(spec_.name + " gave " + std::to_string(out.size()) + " outputs, not 2");
    if (!finite_outputs(out)) return false;
    const float *xyz = mesh_landmarks(out[0], spec_.landmarks, spec_.landmarks_output);
    if (decode_face_flag(out[1], spec_.flag_output) < spec_.min_face_flag) return false;
    if (!std::all_of(xyz, xyz + 3 * spec_.landmarks, [](float v) { return std::isfinite(v); })) return false;

    // landmarks back into the frame
    cv::Mat to_frame;
    cv::invertAffineTransform(to_input, to_frame);
    std::vector<cv::Point2f> in_patch(static_cast<size_t>(spec_.landmarks));
    for (int i = 0; i < spec_.landmarks; ++i) in_patch[static_cast<size_t>(i)] = {xyz[3 * i], xyz[3 * i + 1]};
    cv::transform(in_patch, landmarks_, to_frame);
    return true;
}

std::optional<HeadPose> MeshPnpModel::estimate(const cv::Mat &frame, const Face &face)
{
    // the region: square, rotated so that the eyes are level; its side the box's long side enlarged,
    // or for a face the tracker followed, roi_face_cm of face at the scale the last fit measured
    // (unless the two differ by half: not the same face)
    const cv::Point2f centre(face.box.x + face.box.width / 2, face.box.y + face.box.height / 2);
    const float box_side = std::max(face.box.width, face.box.height) * spec_.roi_scale;
    const float scale_side = static_cast<float>(spec_.roi_face_cm * last_px_per_cm_);
    const bool by_scale = face.followed && scale_side > 0.f && scale_side < 1.5f * box_side && box_side < 1.5f * scale_side;
    const cv::Point2f eyes = face.keypoints[1] - face.keypoints[0];  // the subject's right eye -> left eye
    last_px_per_cm_ = 0.0;
    if (!landmarks_in_region(frame, centre, std::atan2(eyes.y, eyes.x) * 180.0 / M_PI, by_scale ? scale_side : box_side))
        return std::nullopt;

    // the pose of the canonical face that projects onto them
    const double focal = spec_.focal_scale * std::max(frame.cols, frame.rows);
    const cv::Matx33d camera(focal, 0, frame.cols / 2.0, 0, focal, frame.rows / 2.0, 0, 0, 1);
    cv::Vec3d rvec, tvec;
    if (!cv::solvePnP(canonical_, landmarks_, camera, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_SQPNP)) return std::nullopt;
    cv::Matx33d model_to_camera;
    cv::Rodrigues(rvec, model_to_camera);
    HeadPose pose = pose_from_rotation(model_to_camera * kCanonicalToCamera);
    pose.pitch *= spec_.signs[0];
    pose.yaw *= spec_.signs[1];
    pose.roll *= spec_.signs[2];
    if (!std::isfinite(pose.pitch) || !std::isfinite(pose.yaw) || !std::isfinite(pose.roll)) return std::nullopt;

    // the position: the rigid upper face fitted with the camera of --fov, moved to the pivot; its
    // scale sizes the next frame's region
    std::vector<cv::Point2f> rigid_landmarks;
    for (int i : rigid_) rigid_landmarks.push_back(landmarks_[static_cast<size_t>(i)]);
    const std::optional<PositionFit> fit =
        fit_position(rigid_canonical_, rigid_landmarks, frame.size(), position_settings_, front_z_);
    pose.has_position = fit.has_value() && fit->px_per_cm > 0.0;  // the scale too: it sizes the next region
    if (pose.has_position) {
        pose.position = fit->position;
        last_px_per_cm_ = fit->px_per_cm;  // written only when it succeeds: else still 0
    }
    return pose;
}

}  // namespace hkf_estimator
