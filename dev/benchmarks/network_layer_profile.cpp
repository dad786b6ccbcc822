// hkf-bench-layers - where a network's forward pass spends its time in OpenCV's DNN module (the
// shipped runtime): cv::dnn::Net::getPerfProfile after each forward, summed by layer type, medians
// over the runs. For the second model's speed (WHENet's EfficientNet-B0 ran 8x slower in OpenCV 4.6
// than in onnxruntime until its graph was rewritten onto the estimator's own layers: docs/estimator.md).
// The network is loaded as the estimator loads it (load_onnx_network: those layers registered). Then the same network quantized to int8 by OpenCV itself
// (cv::dnn::Net::quantize, calibrated on the same input), its whole pass: the shipped runtime's int8 path.
// usage: hkf-bench-layers MODEL.onnx [WIDTH HEIGHT [RUNS [THREADS]]]   (defaults 224 224 40 1)
// HKF_SIMD chooses the level of hkf's layers, OPENCV_CPU_DISABLE OpenCV's (layer_levels.sh runs every level).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>

#include "onnx_network.hpp"
#include "simd_level.hpp"

namespace {

void usage(FILE *to)
{
    std::fprintf(to, "usage: hkf-bench-layers MODEL.onnx [WIDTH HEIGHT [RUNS [THREADS]]]\n"
                     "  the forward pass's time per layer type in OpenCV's DNN module (medians over RUNS,\n"
                     "  default 40, on THREADS threads, default 1), for an NCHW float input of WIDTH x HEIGHT\n"
                     "  (default 224 x 224)\n");
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

bool whole_number(const char *text, long low, long high, long *out)
{
    char *end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < low || v > high) return false;
    *out = v;
    return true;
}

struct LayerTimes {
    std::string name, type;
    std::vector<double> ms;  // per run
};

struct TypeTimes {
    int layers = 0;
    std::vector<double> ms;  // per run, summed over the type's layers
};

// The command line: 0 to go on, else the exit status (help, version: 0; bad: 2).
struct Options {
    const char *model = nullptr;
    long width = 224, height = 224, runs = 40, threads = 1;
};

int parse(int argc, char **argv, Options *o)
{
    if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "--version") == 0)) {
        if (std::strcmp(argv[1], "--version") == 0) std::printf("hkf-bench-layers %s\n", HKF_VERSION);
        else usage(stdout);
        return -1;
    }
    if (argc < 2 || argc == 3 || argc > 6 ||
        (argc >= 4 && (!whole_number(argv[2], 8, 4096, &o->width) || !whole_number(argv[3], 8, 4096, &o->height))) ||
        (argc >= 5 && !whole_number(argv[4], 3, 100000, &o->runs)) ||
        (argc >= 6 && !whole_number(argv[5], 1, 64, &o->threads))) {
        usage(stderr);
        return 2;
    }
    o->model = argv[1];
    return 0;
}

// An NCHW float input of the options' size, random: the time does not depend on the values.
cv::Mat random_input(const Options &o)
{
    const int shape[] = {1, 3, static_cast<int>(o.height), static_cast<int>(o.width)};
    cv::Mat input(4, shape, CV_32F);
    cv::RNG rng(7);
    rng.fill(input, cv::RNG::NORMAL, 0.0, 1.0);
    return input;
}

// The runs' timings: the whole pass, per layer type, per layer.
struct Profile {
    std::vector<double> total_ms;
    std::map<std::string, TypeTimes> by_type;
    std::vector<LayerTimes> by_layer;
};

// RUNS forward passes (after two not counted), each one's getPerfProfile summed by layer type.
Profile profile(cv::dnn::Net &net, const Options &o)
{
    const cv::Mat input = random_input(o);
    const std::vector<std::string> names = net.getLayerNames();
    const double tick_ms = 1000.0 / cv::getTickFrequency();
    Profile p;
    p.by_layer.resize(names.size());
    for (long run = 0; run < o.runs + 2; ++run) {
        net.setInput(input);
        net.forward();
        std::vector<double> ticks;
        const int64 total = net.getPerfProfile(ticks);
        if (run < 2) continue;
        p.total_ms.push_back(static_cast<double>(total) * tick_ms);
        std::map<std::string, double> this_run;
        for (size_t i = 0; i < ticks.size() && i < names.size(); ++i) {
            const cv::Ptr<cv::dnn::Layer> layer = net.getLayer(net.getLayerId(names[i]));
            const std::string type = layer ? layer->type : "?";
            this_run[type] += ticks[i] * tick_ms;
            p.by_layer[i].name = names[i];
            p.by_layer[i].type = type;
            p.by_layer[i].ms.push_back(ticks[i] * tick_ms);
            if (run == 2) ++p.by_type[type].layers;
        }
        for (const auto &t : this_run) p.by_type[t.first].ms.push_back(t.second);
    }
    return p;
}

void print_by_type(const Profile &p, double total)
{
    std::vector<std::pair<double, std::string>> order;
    for (const auto &t : p.by_type) order.emplace_back(median(t.second.ms), t.first);
    std::sort(order.rbegin(), order.rend());
    std::printf("| layer type | layers (after OpenCV's fusion) | ms (median) | share |\n| --- | ---: | ---: | ---: |\n");
    for (const auto &o : order) {
        const TypeTimes &t = p.by_type.at(o.second);
        if (o.first <= 0.0 && t.layers == 0) continue;
        std::printf("| %s | %d | %.2f | %.0f %% |\n", o.second.c_str(), t.layers, o.first, total > 0 ? 100.0 * o.first / total : 0.0);
    }
}

void print_slowest(const Profile &p)
{
    std::vector<std::pair<double, size_t>> slowest;
    for (size_t i = 0; i < p.by_layer.size(); ++i) slowest.emplace_back(median(p.by_layer[i].ms), i);
    std::sort(slowest.rbegin(), slowest.rend());
    std::printf("\nThe slowest layers:\n\n| layer | type | ms (median) |\n| --- | --- | ---: |\n");
    for (size_t k = 0; k < slowest.size() && k < 10; ++k) {
        const LayerTimes &l = p.by_layer[slowest[k].second];
        std::printf("| %s | %s | %.2f |\n", l.name.c_str(), l.type.c_str(), slowest[k].first);
    }
}

// The median forward pass (ms) of net quantized to int8 by OpenCV (calibrated on the random input); a negative
// value when OpenCV cannot quantize it (said).
double int8_forward_ms(cv::dnn::Net &net, const Options &o)
{
    const cv::Mat input = random_input(o);
    cv::dnn::Net int8;
    try {
        int8 = net.quantize(std::vector<cv::Mat>{input}, CV_32F, CV_32F);
    } catch (const cv::Exception &e) {
        std::fprintf(stderr, "hkf-bench-layers: OpenCV cannot quantize %s: %s\n", o.model, e.what());
        return -1.0;
    }
    std::vector<double> ms;
    const double tick_ms = 1000.0 / cv::getTickFrequency();
    for (long run = 0; run < o.runs + 2; ++run) {
        int8.setInput(input);
        int8.forward();
        std::vector<double> ticks;
        const int64 total = int8.getPerfProfile(ticks);
        if (run >= 2) ms.push_back(static_cast<double>(total) * tick_ms);
    }
    return median(ms);
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    const int status = parse(argc, argv, &o);
    if (status != 0) return status < 0 ? 0 : status;
    cv::dnn::Net net;
    const char *level = nullptr;
    try {
        level = hkf_estimator::layer_kernels_in_use().name;  // HKF_SIMD, or the best this CPU runs
    } catch (const hkf_estimator::EstimatorError &e) {  // a level this CPU cannot run, or none: exit 2
        std::fprintf(stderr, "hkf-bench-layers: %s\n", e.what());
        return 2;
    }
    try {
        net = hkf_estimator::load_onnx_network(o.model, {});
    } catch (const hkf_estimator::EstimatorError &e) {
        std::fprintf(stderr, "hkf-bench-layers: %s\n", e.what());
        return 1;
    }
    cv::setNumThreads(static_cast<int>(o.threads));
    net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
    net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
    const Profile p = profile(net, o);
    const double total = median(p.total_ms);
    std::printf("%s, %ldx%ld, OpenCV %s, hkf's layers at %s, %ld thread%s, %ld runs: forward pass %.2f ms (median)\n\n",
                o.model, o.width, o.height, CV_VERSION, level, o.threads, o.threads == 1 ? "" : "s", o.runs, total);
    print_by_type(p, total);
    print_slowest(p);
    const double int8_ms = int8_forward_ms(net, o);
    if (int8_ms >= 0.0)
        std::printf("\nQuantized to int8 by OpenCV (cv::dnn::Net::quantize): forward pass %.1f ms (median), %.2fx the "
                    "float pass\n", int8_ms, total > 0 ? int8_ms / total : 0.0);
    return 0;
}
