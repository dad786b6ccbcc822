// hkf-estimator - the head-pose estimator process: a camera, video file or
// image folder in, hkf.head_pose_measurement_t on HEAD_POSE_RAW out (see
// pipeline.hpp); or, with --dataset, the evaluation of a head-pose model on a
// labelled image set.
#include <algorithm>
#include <cctype>
#include <climits>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <filesystem>

#include <unistd.h>

#include <lcm/lcm.h>

#include <opencv2/core/utility.hpp>

#include "dataset_eval.hpp"
#include "face_detector.hpp"
#include "frame_source.hpp"
#include "opencv_environment.hpp"
#include "model_spec.hpp"
#include "simd_level.hpp"
#include "pipeline.hpp"
#include "head_pose_estimator.hpp"
#include "hkf/head_pose_measurement_t.hpp"

#include "arguments.h"
#include "model_name.h"

#include "safe_files.h"

namespace {

// The data an installed hkf-estimator ships with, <prefix>/share/hkf/SUB beside
// <prefix>/bin, found from the program's own location so that the prefix may
// move; "" when there is none (the build tree: the compile-time folders).
std::string installed_data(const char *sub)
{
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return "";
    const std::filesystem::path data = self.parent_path().parent_path() / "share" / "hkf" / sub;
    return std::filesystem::is_directory(data, error) ? data.string() : "";
}

std::string default_models_dir()
{
    const std::string installed = installed_data("models");
    return installed.empty() ? HKF_DEFAULT_MODELS_DIR : installed;
}

std::string default_spec_dir()
{
    const std::string installed = installed_data("specs");
    return installed.empty() ? HKF_DEFAULT_SPEC_DIR : installed;
}

constexpr const char *kDefaultSecondModel = "whenet";

struct Options {
    std::string dataset, model = "mesh_pnp", predictions;  // the default keeps up with 60 fps
    // --second-model: by default WHENet beside the mesh (kDefaultSecondModel); "none": the first alone
    std::string second_model;
    bool second_model_given = false;
    std::string models_dir = default_models_dir(), spec_dir = default_spec_dir();
    long limit = 0;
    hkf_estimator::PipelineOptions pipeline;
    hkf_estimator::PositionSettings position;  // --fov, --pivot
    std::string detector = "retina";
    hkf_estimator::DatasetCrop crop = hkf_estimator::DatasetCrop::Live;
};

// --annotate OUT: a video file name in a folder that exists and can be written,
// and not the source. Checked before anything runs; "" or why not.
std::string annotate_path_problem(const std::string &path, const std::string &source)
{
    namespace fs = std::filesystem;
    std::error_code error;
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    if (extension != ".mp4" && extension != ".m4v" && extension != ".mov" && extension != ".avi" && extension != ".mkv")
        return "the name ends in ." + std::string(extension.empty() ? "(nothing)" : extension.substr(1)) +
               "; give a video file: .mp4, .m4v, .mov, .avi or .mkv";
    const fs::path folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
    if (!fs::is_directory(folder, error)) return "the folder " + folder.string() + " does not exist";
    if (access(folder.c_str(), W_OK) != 0) return "the folder " + folder.string() + " cannot be written";
    if (fs::exists(path, error) && !fs::is_regular_file(path, error)) return "it exists and is not a regular file";
    if (!source.empty() && safe_same_file(path.c_str(), source.c_str())) return "it is the source; refusing to write over it";
    if (!source.empty() && safe_writes_over(path.c_str(), source.c_str()))
        return "it is inside the source folder " + source + "; refusing to write there";
    char reason[2 * PATH_MAX + 200];
    if (safe_output_problem(path.c_str(), reason, sizeof reason) != 0) return reason;  // a file this run reads, by identity
    return "";
}

// Every file this run will read, noted by device and inode before any output is opened (safe_files.h), so
// that no output is one of them under another name (a hard link): the source (a video, or a folder's
// images), the dataset's labels and images, the models and their descriptions.
void note_inputs(const Options &o)
{
    for (const std::string *input : {&o.pipeline.source, &o.dataset, &o.models_dir, &o.spec_dir}) {
        if (input->empty()) continue;
        safe_note_read(input->c_str());
        safe_note_folder(input->c_str());
    }
}

void usage(std::ostream &out)
{
    out << "usage: hkf-estimator --source SRC [options]        camera / video / images -> LCM\n"
           "       hkf-estimator --dataset DIR --predictions OUT.csv [--model NAME [--second-model NAME|none]] [--limit N]\n"
           "Finds the driver's face, estimates its head pose and publishes\n"
           "hkf.head_pose_measurement_t on HEAD_POSE_RAW for every frame (valid = false: no face).\n"
           "  --source SRC       a camera (0, /dev/video0), a video file, or a folder of images\n"
           "  --realtime         pace a file at its frame rate (default: as fast as possible)\n"
           "  --fps F            frame rate of an image folder (default 30)\n"
           "  --detector R       the search for a face: retina (default: RetinaFace finds near and\n"
           "                     far faces and profiles, then BlazeFace follows the face), short\n"
           "                     (BlazeFace only, faces within ~2 m) or full\n"
           "                     (BlazeFace only, up to ~5 m)\n"
           "  --region X,Y,W,H   only faces whose centre is in this region (px) are taken\n"
           "  --annotate OUT.mp4 write the video with face box and pose axes (raw thin, filtered thick)\n"
           "  --show             also show it in a window (needs a display)\n"
           "  --lcm-url URL      default udpm://239.255.76.67:7667?ttl=0 (stays on this host)\n"
           "  --channel C        default HEAD_POSE_RAW\n"
           "  --max-frames N     stop after N frames\n"
           "  --second-model NAME  also run this model on its own thread where the first finds no\n"
           "                     pose on the tracked face or measures a large yaw (default whenet;\n"
           "                     none: the first model alone); its measurements go on the same\n"
           "                     channel with the frame's seq and time, and hkf-filter fuses both\n"
           "                     (docs/programs.md: \"Two models on one channel\")\n"
           "  --second-from-yaw DEG  where the second model runs: |yaw| >= DEG (default 10; 0: every frame)\n"
           "  --second-alone-from-yaw DEG  from a camera or --realtime: where the second model's newest\n"
           "                     answer (of a frame within 200 ms) read |yaw| >= DEG, the first model is\n"
           "                     not run and the second measures the frame alone (default 60; 0: never)\n"
           "  --fov DEG          the camera's diagonal field of view, for the head's position (default\n"
           "                     56; unknown: a gain on the distance, docs/estimator.md \"Head position\")\n"
           "  --pivot CM         the point the head turns about, CM behind the nose tip (default 10)\n"
           "--dataset mode evaluates what the tracker runs (with no --model: the mesh, and WHENet where\n"
           "the live pipeline runs it, fused as hkf-filter fuses one frame; --second-model none: one\n"
           "model) on a labelled image set laid out like\n"
           "../shared/data/aflw2000 (labels.csv and images/): finds each face the way live video\n"
           "does (the search on the whole image takes the largest face, then the face is followed\n"
           "in the region around it as on a still face's next frame; a face away from the labelled\n"
           "one counts as not found), writes image,pitch_deg,yaw_deg,roll_deg (hkf angle\n"
           "convention) and prints the MAE per axis, and found faces and MAE per labelled |yaw| bin,\n"
           "over the images whose three angles are within +-99 deg.\n"
           "  --crop live|labels live (default), or the labelled face box as the benchmark's crops\n"
           "                     (a model that needs keypoints: the detected face nearest that box)\n"
           "  --model NAME       mesh_pnp (default: keeps up with 60 fps) or whenet (more accurate at\n"
           "                     large angles, ~30 ms a frame): a description in the model folder\n"
           "  --limit N          only the first N images\n"
           "  --models-dir DIR   converted models (default "
        << default_models_dir() << ", or $HKF_MODELS_DIR)\n"
           "  --spec-dir DIR     model descriptions (default " << default_spec_dir() << ")\n"
           "  --help, --version  this text; the version\n"
           "Environment:\n"
           "  HKF_SIMD           the instruction-set level of the estimator's own layers (WHENet's):\n"
           "                     avx512, avx2 (with FMA), avx (no FMA), sse2 (x86-64; neon on aarch64) or\n"
           "                     default, the best this CPU runs; the start-up line names the level in use\n"
           "  OPENCV_IO_MAX_IMAGE_PIXELS  the largest image decoded, 1 to 33177600 pixels (the default)\n";
}

// --region X,Y,W,H: a region within the largest frame; false when the text is not one.
bool read_region(const std::string &value, cv::Rect2f &region)
{
    float x, y, w, h;
    char extra;
    const auto px = [](float v) { return std::isfinite(v) && std::fabs(v) <= static_cast<float>(hkf_estimator::kMaxFrameSide); };
    if (std::sscanf(value.c_str(), "%f,%f,%f,%f%c", &x, &y, &w, &h, &extra) != 4 || !px(x) || !px(y) || !px(w) ||
        !px(h) || w <= 0 || h <= 0)
        return false;
    region = cv::Rect2f(x, y, w, h);
    return true;
}

// What an option takes: nothing (a switch), text as it is, a number or a whole number within [low, high],
// one of the choices ("a|b"), or a region.
enum class Takes { Nothing, Text, Number, Whole, Choice, Region };

struct OptionSpec {
    const char *name;
    Takes takes;
    double low, high;     // Number, Whole
    const char *choices;  // Choice: "a|b|c"
    const char *wants;    // what a bad value is told it should be
    void (*store)(Options &o, const std::string &text, double number);
};

const std::string kRegionWants = "X,Y,W,H in px (finite, W and H > 0, each within " +
                                 std::to_string(hkf_estimator::kMaxFrameSide) + ")";

// Every option but --help and --version (arguments.h), and where it goes.
const OptionSpec kOptions[] = {
    {"--source", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.pipeline.source = v; }},
    {"--annotate", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.pipeline.annotate_path = v; }},
    {"--lcm-url", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.pipeline.lcm_url = v; }},
    {"--channel", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.pipeline.channel = v; }},
    {"--dataset", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.dataset = v; }},
    {"--model", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.model = v; }},
    {"--predictions", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.predictions = v; }},
    {"--models-dir", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.models_dir = v; }},
    {"--spec-dir", Takes::Text, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) { o.spec_dir = v; }},
    {"--second-model", Takes::Text, 0, 0, nullptr, nullptr,
     [](Options &o, const std::string &v, double) {
         o.second_model = v == "none" ? "" : v;
         o.second_model_given = true;
     }},
    {"--realtime", Takes::Nothing, 0, 0, nullptr, nullptr, [](Options &o, const std::string &, double) { o.pipeline.realtime = true; }},
    {"--show", Takes::Nothing, 0, 0, nullptr, nullptr, [](Options &o, const std::string &, double) { o.pipeline.show = true; }},
    {"--fps", Takes::Number, 0.1, 1000.0, nullptr, "a number from 0.1 to 1000",
     [](Options &o, const std::string &, double n) { o.pipeline.fps_for_images = n; }},
    {"--max-frames", Takes::Whole, 1.0, 1e9, nullptr, "a positive whole number",
     [](Options &o, const std::string &, double n) { o.pipeline.max_frames = static_cast<long>(n); }},
    {"--second-from-yaw", Takes::Number, 0.0, 180.0, nullptr, "degrees from 0 to 180",
     [](Options &o, const std::string &, double n) { o.pipeline.second_from_yaw = static_cast<float>(n); }},
    {"--second-alone-from-yaw", Takes::Number, 0.0, 180.0, nullptr, "degrees from 0 to 180",
     [](Options &o, const std::string &, double n) { o.pipeline.second_alone_from_yaw = static_cast<float>(n); }},
    {"--fov", Takes::Number, 10.0, 170.0, nullptr, "the camera's diagonal field of view, 10 to 170 deg",
     [](Options &o, const std::string &, double n) { o.position.fov_deg = n; }},
    {"--pivot", Takes::Number, 0.0, 30.0, nullptr, "cm behind the nose tip, 0 to 30",
     [](Options &o, const std::string &, double n) { o.position.pivot_cm = n; }},
    {"--limit", Takes::Whole, 1.0, 1e12, nullptr, "a positive whole number",
     [](Options &o, const std::string &, double n) { o.limit = static_cast<long>(n); }},
    {"--detector", Takes::Choice, 0, 0, "short|full|retina", "short, full or retina",
     [](Options &o, const std::string &v, double) { o.detector = v; }},
    {"--crop", Takes::Choice, 0, 0, "live|labels", "live or labels",
     [](Options &o, const std::string &v, double) {
         o.crop = v == "live" ? hkf_estimator::DatasetCrop::Live : hkf_estimator::DatasetCrop::Labels;
     }},
    {"--region", Takes::Region, 0, 0, nullptr, nullptr, [](Options &o, const std::string &v, double) {
         (void)read_region(v, o.pipeline.tracker.region);
     }},
};

const OptionSpec *find_option(const std::string &name)
{
    for (const OptionSpec &spec : kOptions)
        if (name == spec.name) return &spec;
    return nullptr;
}

// 1 when text is one of the choices "a|b|c".
bool is_choice(const std::string &text, const std::string &choices)
{
    return !text.empty() && text.find('|') == std::string::npos &&
           ("|" + choices + "|").find("|" + text + "|") != std::string::npos;
}

// The value of option `spec` into o: true, or false with the reason said.
bool read_value(const OptionSpec &spec, const std::string &value, Options &o)
{
    double number = 0.0;
    bool good = true;
    switch (spec.takes) {
    case Takes::Number: good = argument_number(value.c_str(), spec.low, spec.high, &number) != 0; break;
    case Takes::Whole:
        good = argument_number(value.c_str(), spec.low, spec.high, &number) != 0 && number == std::floor(number);
        break;
    case Takes::Choice: good = is_choice(value, spec.choices); break;
    case Takes::Region: {
        cv::Rect2f region;
        good = read_region(value, region);
        break;
    }
    case Takes::Nothing:
    case Takes::Text: break;
    }
    if (!good) {
        std::cerr << "hkf-estimator: " << spec.name
                  << (spec.takes == Takes::Choice ? std::string(" is ") + spec.wants
                      : spec.takes == Takes::Region ? " wants " + kRegionWants
                                                    : std::string(" wants ") + spec.wants)
                  << ", not '" << value << "'\n";
        return false;
    }
    spec.store(o, value, number);
    return true;
}

// The rules between options, once all are read: 0, or 2 (said).
int check_options(Options &o)
{
    if (o.pipeline.source.empty() == o.dataset.empty()) {
        std::cerr << "hkf-estimator: give either --source SRC or --dataset DIR (see --help)\n";
        return 2;
    }
    // the default pipeline: WHENet beside the mesh (docs/estimator.md: "The default pipeline"), on video
    // and on a dataset alike; WHENet as the first model needs no second
    if (!o.second_model_given && o.model != kDefaultSecondModel) o.second_model = kDefaultSecondModel;
    if (!o.second_model.empty() && o.second_model == o.model) {
        std::cerr << "hkf-estimator: --second-model must differ from --model (" << o.model << ")\n";
        return 2;
    }
    for (const std::string *name : {&o.model, &o.second_model}) {
        if ((name == &o.model || !name->empty()) && !model_name_valid(name->c_str())) {
            std::cerr << "hkf-estimator: a model name has 1 to " << hkf::head_pose_measurement_t::MODEL_NAME_MAX
                      << " letters, digits, '_' or '-' (the limit of head_pose_measurement_t.lcm), not '" << *name << "'\n";
            return 2;
        }
    }
    if (o.pipeline.channel.empty() || o.pipeline.channel.size() > LCM_MAX_CHANNEL_NAME_LENGTH) {
        std::cerr << "hkf-estimator: a channel name has 1 to " << LCM_MAX_CHANNEL_NAME_LENGTH << " characters, not '"
                  << o.pipeline.channel << "'\n";
        return 2;
    }
    if (!o.dataset.empty() && o.predictions.empty()) {
        std::cerr << "hkf-estimator: --dataset DIR needs --predictions OUT.csv (see --help)\n";
        return 2;
    }
    return 0;
}

void usage_to(FILE *to)
{
    std::ostringstream text;
    usage(text);
    std::fputs(text.str().c_str(), to);
}

// 0 = run, 1 = help shown, 2 = bad arguments
int parse(int argc, char **argv, Options &o)
{
    if (const char *env = std::getenv("HKF_MODELS_DIR"); env != nullptr && *env != '\0') o.models_dir = env;  // '': unset
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (argument_help_or_version(argv[i], "hkf-estimator", usage_to)) return 1;
        const OptionSpec *spec = find_option(arg);
        if (spec != nullptr && spec->takes == Takes::Nothing) {
            spec->store(o, "", 0.0);
            continue;
        }
        if (spec == nullptr || i + 1 >= argc) {
            std::cerr << "hkf-estimator: " << (spec == nullptr ? "unknown" : "incomplete") << " argument '" << arg
                      << "' (see --help)\n";
            return 2;
        }
        if (!read_value(*spec, argv[++i], o)) return 2;
    }
    return check_options(o);
}

// The instruction-set level the estimator's own layers run at (HKF_SIMD, or the best this CPU runs),
// said at start-up: false (said) for an HKF_SIMD that is not a level or that this CPU cannot run.
bool announce_layer_level()
{
    try {
        const hkf_estimator::LayerKernels &in_use = hkf_estimator::layer_kernels_in_use();
        std::string supported;
        for (hkf_estimator::SimdLevel level : hkf_estimator::simd_levels_supported())
            supported += std::string(supported.empty() ? "" : " ") + hkf_estimator::layer_kernels_of(level).name;
        std::fprintf(stderr, "hkf-estimator: the estimator's own layers at %s (this CPU runs %s; HKF_SIMD chooses)\n",
                     in_use.name, supported.c_str());
        return true;
    } catch (const hkf_estimator::EstimatorError &e) {
        std::cerr << "hkf-estimator: " << e.what() << "\n";
        return false;
    }
}

// What a dataset run measured: the totals, then faces found and MAE per labelled |yaw| bin.
void print_dataset_result(const hkf_estimator::EvalResult &r, const Options &o)
{
    using hkf_estimator::EvalResult;
    const std::string what = o.second_model.empty()
        ? o.model
        : "the default pipeline (" + o.model + "; " + o.second_model + " where its |yaw| >= " +
              std::to_string(static_cast<int>(o.pipeline.second_from_yaw)) + " deg or it has no pose, fused as hkf-filter fuses "
              "one frame, alone from " + std::to_string(static_cast<int>(hkf_estimator::kSecondAloneFromYaw)) + " deg)";
    std::printf("%s on %s (%s): %ld images (%ld unreadable, %ld without a face found), %ld within +-99 deg\n",
                what.c_str(), o.dataset.c_str(),
                o.crop == hkf_estimator::DatasetCrop::Live ? "live path: detector on the whole image" : "labelled face boxes",
                r.images, r.unreadable, r.no_face, r.evaluated);
    if (o.crop == hkf_estimator::DatasetCrop::Live)
        std::printf("faces not found: %ld, of which the detector took another face: %ld\n", r.no_face, r.wrong_face);
    std::printf("MAE deg: pitch %.2f, yaw %.2f, roll %.2f, mean %.2f; %.1f ms per image (%d threads)\n",
                r.mae[0], r.mae[1], r.mae[2], (r.mae[0] + r.mae[1] + r.mae[2]) / 3.0,
                r.images > r.unreadable ? 1000.0 * r.seconds / static_cast<double>(r.images - r.unreadable) : 0.0,
                cv::getNumThreads());
    for (int b = 0; b < EvalResult::kYawBins; ++b) {
        const long found = r.bin_images[b] - r.bin_no_face[b];
        std::printf("labelled |yaw| %2.0f-%2.0f deg: %4ld images, %4ld faces found (%5.1f %%), MAE deg: pitch %.2f, yaw %.2f, "
                    "roll %.2f, mean %.2f\n",
                    EvalResult::kYawBinEdges[b], EvalResult::kYawBinEdges[b + 1], r.bin_images[b], found,
                    r.bin_images[b] > 0 ? 100.0 * static_cast<double>(found) / static_cast<double>(r.bin_images[b]) : 0.0,
                    r.bin_mae[b][0], r.bin_mae[b][1], r.bin_mae[b][2],
                    (r.bin_mae[b][0] + r.bin_mae[b][1] + r.bin_mae[b][2]) / 3.0);
    }
}

// --dataset: the run over the labelled images, its predictions written, its figures printed. The predictions
// are opened first (safe_open_output): never the dataset's labels or images, the models or their descriptions,
// never a named pipe that nothing reads.
int run_dataset(const hkf_estimator::DatasetRun &run, const Options &o)
{
    const char *const inputs[] = {o.dataset.c_str(), o.models_dir.c_str(), o.spec_dir.c_str()};
    FILE *file = safe_open_output(o.predictions.c_str(), "w", inputs, 3, "hkf-estimator");
    if (file == nullptr) throw hkf_estimator::EstimatorError("--predictions " + o.predictions + " refused");
    std::ostringstream predictions;
    auto last = std::chrono::steady_clock::now();
    const hkf_estimator::EvalResult r = evaluate_dataset(run, predictions, [&](long done, long total) {
        const auto now = std::chrono::steady_clock::now();
        if (done == total || now - last > std::chrono::seconds(2)) {
            std::cerr << "hkf-estimator: " << done << "/" << total << " images\n";
            last = now;
        }
    });
    const std::string text = predictions.str();
    const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    if (safe_close(file) != 0 || !written) throw hkf_estimator::EstimatorError("error writing " + o.predictions + " (a full disk?)");
    print_dataset_result(r, o);
    return r.evaluated > 0 ? 0 : 1;
}

// OpenCV reads its image size cap as it loads, before main: without one in the environment, run again
// with ours (opencv_environment.hpp), so that a larger image is refused from its header, not decoded first
// (a 9000 x 9000 image took 360 MB). Only where images are read (a folder of them, --dataset): a video or
// a camera never meets the cap, and the second start doubled every start (0.14 s more on a Zen 4).
// The program's own path is executed, not /proc/self/exe, so that the process keeps its name (pgrep -x
// hkf-estimator). Should the exec fail, the cap is checked after decoding. With the variable already set
// (by a user, or under valgrind, whose /proc/self/exe is its own), nothing is re-run.
void run_again_with_the_image_cap(const Options &o, char **argv)
{
    std::error_code not_a_folder;
    if (o.dataset.empty() && !std::filesystem::is_directory(o.pipeline.source, not_a_folder)) return;
    if (std::getenv("OPENCV_IO_MAX_IMAGE_PIXELS") != nullptr) return;
    if (*hkf_estimator::opencv_environment_problem() != '\0') return;  // a variable refused: said and exit 2 (start_checks)
    std::error_code error;
    const std::string self = std::filesystem::read_symlink("/proc/self/exe", error).string();
    setenv("OPENCV_IO_MAX_IMAGE_PIXELS", std::to_string(hkf_estimator::kMaxFramePixels).c_str(), 0);
    if (!error) execv(self.c_str(), argv);
}

// What is checked once the options are read, before any model loads: the image cap's variable, the
// layers' level, then the inputs noted and the --annotate output checked against them. false (said): exit 2.
bool start_checks(const Options &o)
{
    if (*hkf_estimator::opencv_environment_problem() != '\0') {  // settled before OpenCV loaded (opencv_environment.hpp)
        std::cerr << "hkf-estimator: " << hkf_estimator::opencv_environment_problem() << "\n";
        return false;
    }
    if (!announce_layer_level()) return false;
    note_inputs(o);
    if (o.pipeline.annotate_path.empty()) return true;
    const std::string problem = annotate_path_problem(o.pipeline.annotate_path, o.pipeline.source);
    if (!problem.empty()) std::cerr << "hkf-estimator: --annotate " << o.pipeline.annotate_path << ": " << problem << "\n";
    return problem.empty();
}

}  // namespace

int main(int argc, char **argv)
{
    using namespace hkf_estimator;
    Options o;
    safe_files_fail_writes_past_size_limit();  // a file-size limit: a reported write error, not SIGXFSZ
    switch (parse(argc, argv, o)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }
    run_again_with_the_image_cap(o, argv);
    if (!start_checks(o)) return 2;
    try {
        const std::unique_ptr<HeadPoseEstimator> model = make_estimator(load_model_spec(o.spec_dir, o.model, o.models_dir));
        model->set_position_settings(o.position);
        // retina: RetinaFace searches the frame (near, far and turned faces), BlazeFace short
        // range follows the face in the region around it
        const DetectorRange search_range = o.detector == "short"  ? DetectorRange::Short
                                           : o.detector == "full" ? DetectorRange::Full
                                                                  : DetectorRange::Retina;
        FaceDetector detector(o.models_dir, search_range);
        std::unique_ptr<FaceDetector> region;
        if (search_range == DetectorRange::Retina) region = std::make_unique<FaceDetector>(o.models_dir, DetectorRange::Short);
        const TrackerDetectors detectors{&detector, region ? region.get() : &detector};
        std::unique_ptr<HeadPoseEstimator> second;
        if (!o.second_model.empty()) {
            second = make_estimator(load_model_spec(o.spec_dir, o.second_model, o.models_dir));
            second->set_position_settings(o.position);
        }
        if (!o.pipeline.source.empty()) return run_pipeline(*model, detectors, o.pipeline, second.get());
        std::unique_ptr<FrameFusion> fusion;
        if (second) fusion = std::make_unique<FrameFusion>(o.model, o.second_model, o.pipeline.second_from_yaw);
        return run_dataset(DatasetRun{model.get(), second.get(), fusion.get(), detectors, o.crop, o.dataset, o.limit}, o);
    } catch (const EstimatorError &e) {
        std::cerr << "hkf-estimator: " << e.what() << "\n";
        return 1;
    } catch (const std::exception &e) {  // OpenCV's, the standard library's: an error, never an abort
        std::cerr << "hkf-estimator: " << e.what() << "\n";
        return 1;
    }
}
