// model_spec.cpp - see model_spec.hpp.
#include "model_spec.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace hkf_estimator {
namespace {

std::string trim(const std::string &s)
{
    const auto begin = s.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return "";
    return s.substr(begin, s.find_last_not_of(" \t\r\n") - begin + 1);
}

template <typename T>
T parse_one(std::istringstream &in, const std::string &where)
{
    T value;
    if (!(in >> value)) throw EstimatorError(where + ": a value is missing or malformed");
    return value;
}

void expect_end(std::istringstream &in, const std::string &where)
{
    std::string rest;
    if (in >> rest) throw EstimatorError(where + ": unexpected '" + rest + "'");
}

// The keys of the network's input: file, input, color, scale, mean, std, signs. False for another key.
bool read_input_key(ModelSpec &spec, const std::string &key, std::istringstream &in, const std::string &where,
                    const std::string &models_dir)
{
    if (key == "file") {
        spec.file = models_dir + "/" + parse_one<std::string>(in, where);
    } else if (key == "input") {
        spec.input_width = parse_one<int>(in, where);
        spec.input_height = parse_one<int>(in, where);
        if (spec.input_width < 8 || spec.input_height < 8 || spec.input_width > 4096 || spec.input_height > 4096)
            throw EstimatorError(where + ": input size out of range");
    } else if (key == "color") {
        const auto c = parse_one<std::string>(in, where);
        if (c != "rgb" && c != "bgr") throw EstimatorError(where + ": color is rgb or bgr");
        spec.rgb = c == "rgb";
    } else if (key == "scale") {
        spec.scale = parse_one<float>(in, where);
    } else if (key == "mean" || key == "std" || key == "signs") {
        auto &target = key == "mean" ? spec.mean : key == "std" ? spec.std : spec.signs;
        for (float &v : target) v = parse_one<float>(in, where);
        if (key == "std")
            for (float v : target)
                if (!(v > 0.f)) throw EstimatorError(where + ": std must be positive");
    } else {
        return false;
    }
    return true;
}

// The keys of the network's output: decoder, its bins or landmarks, face_flag, canonical. False for another key.
bool read_output_key(ModelSpec &spec, const std::string &key, std::istringstream &in, const std::string &where,
                     const std::string &models_dir)
{
    if (key == "decoder") {
        spec.decoder = parse_one<std::string>(in, where);
        if (spec.decoder != "angle_bins" && spec.decoder != "landmarks_pnp")
            throw EstimatorError(where + ": unknown decoder '" + spec.decoder + "' (angle_bins, landmarks_pnp)");
    } else if (key == "yaw_bins" || key == "pitch_bins" || key == "roll_bins") {
        AngleBins &b = key == "yaw_bins" ? spec.yaw : key == "pitch_bins" ? spec.pitch : spec.roll;
        b.output = parse_one<std::string>(in, where);
        b.bins = parse_one<int>(in, where);
        b.step = parse_one<float>(in, where);
        b.offset = parse_one<float>(in, where);
        if (b.bins < 2 || b.bins > 10000 || !(b.step > 0.f)) throw EstimatorError(where + ": bad bins");
    } else if (key == "landmarks") {
        spec.landmarks_output = parse_one<std::string>(in, where);
        spec.landmarks = parse_one<int>(in, where);
        if (spec.landmarks < 6 || spec.landmarks > 100000) throw EstimatorError(where + ": bad landmark count");
    } else if (key == "face_flag") {
        spec.flag_output = parse_one<std::string>(in, where);
        spec.min_face_flag = parse_one<float>(in, where);
    } else if (key == "canonical") {
        spec.canonical = models_dir + "/" + parse_one<std::string>(in, where);
    } else {
        return false;
    }
    return true;
}

// The keys of the face's crop: roi_scale, focal_scale, roi_face_cm, crop_margin, and the tried variants
// (flip_average, profile_from, profile_margin, profile_shift). False for another key.
bool read_crop_key(ModelSpec &spec, const std::string &key, std::istringstream &in, const std::string &where)
{
    if (key == "roi_scale" || key == "focal_scale") {
        float &target = key == "roi_scale" ? spec.roi_scale : spec.focal_scale;
        target = parse_one<float>(in, where);
        if (!(target > 0.f && target < 100.f))
            throw EstimatorError(where + ": " + key + " must be above 0 and below 100");
    } else if (key == "roi_face_cm") {
        spec.roi_face_cm = parse_one<float>(in, where);
        if (!(spec.roi_face_cm >= 0.f && spec.roi_face_cm < 1000.f)) throw EstimatorError(where + ": roi_face_cm 0..1000");
    } else if (key == "crop_margin" || key == "profile_margin") {
        float &target = key == "crop_margin" ? spec.crop_margin : spec.profile_margin;
        target = parse_one<float>(in, where);
        if (!(target >= 0.f && target <= 2.f)) throw EstimatorError(where + ": " + key + " 0..2");
    } else if (key == "profile_from" || key == "profile_shift") {
        float &target = key == "profile_from" ? spec.profile_from_deg : spec.profile_shift;
        target = parse_one<float>(in, where);
        if (!(std::fabs(target) <= 180.f)) throw EstimatorError(where + ": " + key + " -180..180");
    } else if (key == "flip_average") {
        const auto v = parse_one<std::string>(in, where);
        if (v != "yes" && v != "no") throw EstimatorError(where + ": flip_average is yes or no");
        spec.flip_average = v == "yes";
    } else {
        return false;
    }
    return true;
}

// Every key the decoder needs is there.
void check_required(const ModelSpec &spec, const std::map<std::string, bool> &seen, const std::string &path)
{
    for (const char *required : {"file", "input", "decoder"})
        if (seen.count(required) == 0) throw EstimatorError(path + ": '" + required + "' is missing");
    const auto required = spec.decoder == "angle_bins" ? std::vector<const char *>{"yaw_bins", "pitch_bins", "roll_bins"}
                                                       : std::vector<const char *>{"landmarks", "face_flag", "canonical"};
    for (const char *key : required)
        if (seen.count(key) == 0) throw EstimatorError(path + ": '" + key + "' is missing");
}

}  // namespace

ModelSpec load_model_spec(const std::string &spec_dir, const std::string &name, const std::string &models_dir)
{
    const std::string path = spec_dir + "/" + name + ".model";
    std::ifstream file(path);
    if (!file) throw EstimatorError("no model description " + path + " (--model names a file in " + spec_dir + ")");
    ModelSpec spec;
    spec.name = name;
    std::map<std::string, bool> seen;
    std::string line;
    for (int number = 1; std::getline(file, line); ++number) {
        const std::string text = trim(line.substr(0, line.find('#')));
        if (text.empty()) continue;
        const auto eq = text.find('=');
        const std::string where = path + ":" + std::to_string(number);
        if (eq == std::string::npos) throw EstimatorError(where + ": expected KEY = VALUE");
        const std::string key = trim(text.substr(0, eq));
        std::istringstream in(trim(text.substr(eq + 1)));
        seen[key] = true;
        if (!read_input_key(spec, key, in, where, models_dir) && !read_output_key(spec, key, in, where, models_dir) &&
            !read_crop_key(spec, key, in, where))
            throw EstimatorError(where + ": unknown key '" + key + "'");
        expect_end(in, where);
    }
    check_required(spec, seen, path);
    return spec;
}

}  // namespace hkf_estimator
