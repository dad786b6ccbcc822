// hkf-estimator - the head-pose estimator process. This version evaluates a
// head-pose model on a labelled image set (the face pipeline on cameras and
// videos, publishing over LCM, comes next).
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include <opencv2/core/utility.hpp>

#include "dataset_eval.hpp"
#include "model_spec.hpp"
#include "pose_model.hpp"

namespace {

struct Options {
    std::string dataset, model = "whenet", predictions;
    std::string models_dir = HKF_DEFAULT_MODELS_DIR, spec_dir = HKF_DEFAULT_SPEC_DIR;
    long limit = 0;
};

void usage(std::ostream &out)
{
    out << "usage: hkf-estimator --dataset DIR --predictions OUT.csv [--model NAME] [--limit N]\n"
           "Evaluates a head-pose model on a labelled image set laid out like ../shared/data/aflw2000\n"
           "(labels.csv and images/): crops each face from its label's box, writes\n"
           "image,pitch_deg,yaw_deg,roll_deg (hkf angle convention) and prints the MAE per axis over\n"
           "the images whose three angles are within +-99 deg.\n"
           "  --model NAME       a description in the model folder (default whenet)\n"
           "  --limit N          only the first N images\n"
           "  --models-dir DIR   converted models (default " HKF_DEFAULT_MODELS_DIR ", or $HKF_MODELS_DIR)\n"
           "  --spec-dir DIR     model descriptions (default " HKF_DEFAULT_SPEC_DIR ")\n"
           "  --help             this text\n";
}

// 0 = run, 1 = help shown, 2 = bad arguments
int parse(int argc, char **argv, Options &o)
{
    if (const char *env = std::getenv("HKF_MODELS_DIR")) o.models_dir = env;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            usage(std::cout);
            return 1;
        }
        if (i + 1 >= argc) {
            std::cerr << "hkf-estimator: unknown or incomplete argument '" << arg << "' (see --help)\n";
            return 2;
        }
        const std::string value = argv[++i];
        if (arg == "--dataset") o.dataset = value;
        else if (arg == "--model") o.model = value;
        else if (arg == "--predictions") o.predictions = value;
        else if (arg == "--models-dir") o.models_dir = value;
        else if (arg == "--spec-dir") o.spec_dir = value;
        else if (arg == "--limit") {
            char *end = nullptr;
            o.limit = std::strtol(value.c_str(), &end, 10);
            if (*end != '\0' || o.limit < 1) {
                std::cerr << "hkf-estimator: --limit wants a positive whole number, not '" << value << "'\n";
                return 2;
            }
        } else {
            std::cerr << "hkf-estimator: unknown argument '" << arg << "' (see --help)\n";
            return 2;
        }
    }
    if (o.dataset.empty() || o.predictions.empty()) {
        std::cerr << "hkf-estimator: --dataset DIR and --predictions OUT.csv are required (see --help)\n";
        return 2;
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    using namespace hkf_estimator;
    Options o;
    switch (parse(argc, argv, o)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }
    try {
        PoseModel model(load_model_spec(o.spec_dir, o.model, o.models_dir));
        std::ofstream predictions(o.predictions);
        if (!predictions) throw EstimatorError("cannot write " + o.predictions);
        auto last = std::chrono::steady_clock::now();
        const EvalResult r = evaluate_dataset(model, o.dataset, o.limit, predictions, [&](long done, long total) {
            const auto now = std::chrono::steady_clock::now();
            if (done == total || now - last > std::chrono::seconds(2)) {
                std::cerr << "hkf-estimator: " << done << "/" << total << " images\n";
                last = now;
            }
        });
        predictions.close();
        if (!predictions) throw EstimatorError("error writing " + o.predictions);
        std::printf("%s on %s: %ld images (%ld unreadable), %ld within +-99 deg\n", o.model.c_str(), o.dataset.c_str(),
                    r.images, r.unreadable, r.evaluated);
        std::printf("MAE deg: pitch %.2f, yaw %.2f, roll %.2f, mean %.2f; model %.1f ms per image (%d threads)\n",
                    r.mae[0], r.mae[1], r.mae[2], (r.mae[0] + r.mae[1] + r.mae[2]) / 3.0,
                    r.images > r.unreadable ? 1000.0 * r.seconds / static_cast<double>(r.images - r.unreadable) : 0.0,
                    cv::getNumThreads());
        return r.evaluated > 0 ? 0 : 1;
    } catch (const EstimatorError &e) {
        std::cerr << "hkf-estimator: " << e.what() << "\n";
        return 1;
    }
}
