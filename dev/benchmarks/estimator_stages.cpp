// hkf-bench-estimator - per-stage cost of the estimator on 640x480 frames, in
// OpenCV DNN: BlazeFace and RetinaFace on the whole frame, the tracked search (a region
// around the face), and each head-pose model. Also writes those frames as a
// 60 fps video, for timing the whole process as a 60 fps camera would feed it.
// usage: hkf-bench-estimator VIDEO MODELS_DIR SPEC_DIR OUT_640x480_60fps.mp4
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "face_detector.hpp"
#include "face_tracker.hpp"
#include "head_pose_estimator.hpp"
#include "model_spec.hpp"

using namespace hkf_estimator;

static void report(const char *stage, std::vector<double> ms)
{
    std::sort(ms.begin(), ms.end());
    std::printf("| %s | %.1f | %.1f | %.0f |\n", stage, ms[ms.size() / 2], ms[static_cast<size_t>(0.99 * static_cast<double>(ms.size() - 1))],
                1000.0 / ms[ms.size() / 2]);
}

static std::vector<double> time_each(const std::vector<cv::Mat> &frames, const std::function<void(const cv::Mat &)> &work)
{
    std::vector<double> ms;
    for (const cv::Mat &f : frames) {
        const auto t0 = std::chrono::steady_clock::now();
        work(f);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    return ms;
}

int main(int argc, char **argv)
{
    if (argc == 2 && (std::strcmp(argv[1], "--version") == 0 || std::strcmp(argv[1], "--help") == 0)) {
        if (std::strcmp(argv[1], "--version") == 0) std::printf("hkf-bench-estimator %s\n", HKF_VERSION);
        else std::printf("usage: hkf-bench-estimator VIDEO MODELS_DIR SPEC_DIR OUT_640x480_60fps.mp4\n");
        return 0;
    }
    if (argc != 5) {
        std::fprintf(stderr, "usage: hkf-bench-estimator VIDEO MODELS_DIR SPEC_DIR OUT_640x480_60fps.mp4\n");
        return 2;
    }
    cv::VideoCapture in(argv[1]);
    std::vector<cv::Mat> frames;
    cv::Mat f;
    while (frames.size() < 300 && in.read(f)) {  // letterboxed into 640x480
        cv::Mat small, canvas(480, 640, CV_8UC3, cv::Scalar(0, 0, 0));
        const double s = std::min(640.0 / f.cols, 480.0 / f.rows);
        cv::resize(f, small, cv::Size(), s, s, cv::INTER_AREA);
        small.copyTo(canvas(cv::Rect((640 - small.cols) / 2, (480 - small.rows) / 2, small.cols, small.rows)));
        frames.push_back(canvas);
    }
    if (frames.empty()) {
        std::fprintf(stderr, "hkf-bench-estimator: no frames in %s\n", argv[1]);
        return 1;
    }
    cv::VideoWriter out(argv[4], cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 60.0, cv::Size(640, 480));
    for (const cv::Mat &frame : frames) out.write(frame);
    out.release();

    FaceDetector detector(argv[2], DetectorRange::Short);
    FaceTracker tracker(detector, TrackerSettings{});
    std::vector<Face> faces(frames.size());
    std::printf("Per-frame cost on %zu frames of 640x480 video, OpenCV %s DNN, %d threads:\n\n", frames.size(),
                CV_VERSION, cv::getNumThreads());
    std::printf("| stage | p50 ms | p99 ms | frames/s at p50 |\n| --- | ---: | ---: | ---: |\n");
    report("BlazeFace short range, whole frame", time_each(frames, [&](const cv::Mat &m) { detector.detect(m); }));
    FaceDetector retina(argv[2], DetectorRange::Retina);  // the default search: start and re-acquire
    report("RetinaFace, whole frame (the search at start and re-acquire)",
           time_each(frames, [&](const cv::Mat &m) { retina.detect(m); }));
    size_t i = 0;
    report("tracked face search (region around the face)", time_each(frames, [&](const cv::Mat &m) {
               faces[i] = tracker.track(m, static_cast<int64_t>(i) * 16667).value_or(Face{});
               ++i;
           }));
    for (const char *name : {"whenet", "mesh_pnp"}) {
        auto model = make_estimator(load_model_spec(argv[3], name, argv[2]));
        i = 0;
        const std::string label = std::string(name) + (std::string(name) == "whenet" ? " (crop + network + decode)" : " (warp + mesh + solvePnP)");
        report(label.c_str(), time_each(frames, [&](const cv::Mat &m) { model->estimate(m, faces[i++]); }));
    }
    return 0;
}
