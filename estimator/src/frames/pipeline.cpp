// pipeline.cpp - see pipeline.hpp.
#include "pipeline.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "lcm_file_url.h"
#include "written_video.hpp"
#include <opencv2/highgui.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "camera_pictures.hpp"
#include "frame_capture.hpp"
#include "frame_source.hpp"
#include "hkf/head_pose_measurement_t.hpp"
#include "hkf/head_pose_t.hpp"
#include "pose_drawing.hpp"
#include "second_model.hpp"

namespace hkf_estimator {
namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int) { stop_requested = true; }

struct FilteredPose {
    std::mutex mutex;
    bool have = false;
    HeadPose pose;
};

// HEAD_POSE through LCM's C API: the C++ API's member-function subscription
// (LCMMHSubscription in LCM 1.3.1's header) fails UBSan's vptr check.
extern "C" void on_filtered_pose(const lcm_recv_buf_t *rbuf, const char *, void *user)
{
    hkf::head_pose_t msg;
    if (msg.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) return;  // not a pose: ignored
    FilteredPose *filtered = static_cast<FilteredPose *>(user);
    std::lock_guard<std::mutex> lock(filtered->mutex);
    filtered->pose = HeadPose{msg.pitch, msg.yaw, msg.roll};
    filtered->have = true;
}

double percentile(std::vector<double> v, double q)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

// The measurement message for a frame.
hkf::head_pose_measurement_t measurement_message(int64_t utime, int64_t seq, const std::string &model_name,
                                                 const std::optional<Face> &face, const HeadPose &pose, double inference_ms)
{
    hkf::head_pose_measurement_t m;
    m.utime = utime;
    m.seq = seq;
    m.model = model_name;
    m.valid = face.has_value();
    m.pitch = pose.pitch;
    m.yaw = pose.yaw;
    m.roll = pose.roll;
    for (int i = 0; i < 4; ++i) m.face_box[i] = 0.f;
    m.detection_score = face ? face->score : 0.f;
    if (face) {
        m.face_box[0] = face->box.x;
        m.face_box[1] = face->box.y;
        m.face_box[2] = face->box.br().x;
        m.face_box[3] = face->box.br().y;
    }
    m.inference_us = static_cast<int64_t>(inference_ms * 1000.0);
    m.x = m.y = m.z = 0.f;  // z = 0: no position
    if (face && pose.has_position) {
        m.x = pose.position.x;
        m.y = pose.position.y;
        m.z = pose.position.z;
    }
    return m;
}

// OpenCV DNN's first forward pass of a network costs several of the next: spent
// here, before capture starts, not on the first frames of a camera.
void warm_up(TrackerDetectors detectors)
{
    const cv::Mat blank(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
    detectors.search->detect(blank);
    if (detectors.region != detectors.search) detectors.region->detect(blank);
}

// The frame with the face, the raw pose (and position) and the last filtered pose drawn, as
// hkf-annotate draws them (pose_drawing.hpp), with the face's keypoints.
cv::Mat annotated_frame(const cv::Mat &frame, const std::optional<Face> &face, const HeadPose &pose, FilteredPose &filtered)
{
    cv::Mat image = frame.clone();
    std::optional<HeadPose> last_filtered;
    {
        std::lock_guard<std::mutex> lock(filtered.mutex);
        if (filtered.have) last_filtered = filtered.pose;
    }
    if (face) draw_face(image, *face);
    draw_annotation(image, face ? std::optional<cv::Rect2f>(face->box) : std::nullopt,
                    face ? std::optional<HeadPose>(pose) : std::nullopt, last_filtered);
    return image;
}

// --annotate's video: opened on the first frame, at its size (a source that changes
// size is scaled to it, counted); closed whole however the run ends.
class AnnotatedVideo {
public:
    explicit AnnotatedVideo(std::string path) : path_(std::move(path)) {}
    void write(cv::Mat image, double fps)
    {
        if (!writer_.isOpened()) {
            size_ = image.size();
            if (!writer_.open(path_, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps, size_))
                throw EstimatorError("cannot write the video " + path_);
        }
        if (image.size() != size_) {
            cv::Mat scaled;
            cv::resize(image, scaled, size_, 0, 0, cv::INTER_AREA);
            image = scaled;
            ++resized_;
        }
        writer_.write(image);
        ++written_;
    }
    void close()
    {
        if (writer_.isOpened()) writer_.release();
    }
    long resized() const { return resized_; }
    // After close: "" when the video opens and holds every frame written (written_video.hpp).
    std::string problem() const { return written_video_problem(path_, written_); }

private:
    std::string path_;
    cv::VideoWriter writer_;
    cv::Size size_;
    long resized_ = 0, written_ = 0;
};

// What the run counted, for the summary and the exit status.
struct RunCounts {
    long frames = 0, with_face = 0, publish_failures = 0;
    long first_set_aside = 0;  // frames left to the second model alone (first_model_set_aside)
    unsigned long published = 0;  // measurements LCM took: a file:// log must hold them all
    std::vector<double> latency_ms, inference_ms, second_latency_ms;
    std::vector<double> second_before_ms, second_waited_ms;  // the second's latency: until it was asked, then queued
};

// What the frame loop works with: the run's parts, which run_pipeline sets up and owns.
struct FrameLoop {
    const PipelineOptions &options;
    HeadPoseEstimator &model;
    HeadPoseEstimator *second;  // nullptr without one
    const FrameSource &source;
    lcm::LCM &lcm;
    std::mutex &lcm_mutex;  // LCM is published to from this thread and the second model's; one at a time
    RunCounts &counts;      // publish_failures and second_latency_ms under lcm_mutex
    FaceTracker &tracker;
    AnnotatedVideo &video;
    FilteredPose &filtered;
    bool show, drop_old;
    std::unique_ptr<SecondModelWorker> second_worker;
    std::unique_ptr<CameraPictures> pictures;  // nullptr where the output is a log file (no view listens there)
    int64_t seq = 0;
};

// The second model on its own thread (nullptr without one): its measurements published on
// the channel as they come, their capture->publish latency counted.
std::unique_ptr<SecondModelWorker> start_second_model(FrameLoop &loop)
{
    HeadPoseEstimator *second = loop.second;
    if (second == nullptr) return nullptr;
    std::fprintf(stderr, "hkf-estimator: second model %s where %s finds no pose or |yaw| >= %.0f deg\n",
                 second->spec().name.c_str(), loop.model.spec().name.c_str(),
                 static_cast<double>(loop.options.second_from_yaw));
    return std::make_unique<SecondModelWorker>(*second, [second, &loop](const SecondModelResult &r) {
        std::optional<Face> face;
        if (r.pose) face = r.job.face;
        const hkf::head_pose_measurement_t m = measurement_message(r.job.utime, r.job.seq, second->spec().name, face,
                                                                   r.pose.value_or(HeadPose{}), r.inference_ms);
        std::lock_guard<std::mutex> lock(loop.lcm_mutex);
        if (loop.lcm.publish(loop.options.channel, &m) != 0) ++loop.counts.publish_failures;
        else ++loop.counts.published;
        const int64_t from = loop.source.live() ? r.job.utime : r.job.taken_utime;
        loop.counts.second_latency_ms.push_back(static_cast<double>(wall_utime() - from) / 1000.0);
        loop.counts.second_before_ms.push_back(static_cast<double>(r.job.asked_utime - from) / 1000.0);
        loop.counts.second_waited_ms.push_back(r.waited_ms);
    });
}

// The run's summary on stdout.
void print_summary(const FrameLoop &loop, double seconds, const LatestFrame &slot, const StallWatch &stall,
                   bool capture_hung)
{
    const RunCounts &counts = loop.counts;
    std::printf("hkf-estimator: %ld frames, %ld with a face, %.1f fps; capture->publish ms p50 %.1f p99 %.1f; "
                "inference ms p50 %.1f; %ld dropped; %ld full-frame face searches; %ld stalls of the source\n",
                counts.frames, counts.with_face, seconds > 0 ? static_cast<double>(counts.frames) / seconds : 0.0,
                percentile(counts.latency_ms, 0.5), percentile(counts.latency_ms, 0.99), percentile(counts.inference_ms, 0.5),
                slot.dropped(), loop.tracker.full_frame_searches(), stall.stalls());
    if (loop.second_worker)
        std::printf("hkf-estimator: second model %s: %ld frames asked for, %ld measured, %ld skipped (it was busy); "
                    "capture->publish ms p50 %.1f p99 %.1f; inference ms p50 %.1f\n",
                    loop.second->spec().name.c_str(), loop.second_worker->asked(), loop.second_worker->done(),
                    loop.second_worker->skipped(), percentile(counts.second_latency_ms, 0.5),
                    percentile(counts.second_latency_ms, 0.99), percentile(loop.second_worker->inference_ms(), 0.5));
    if (loop.second_worker && loop.drop_old && loop.options.second_alone_from_yaw > 0.f)
        std::printf("hkf-estimator: first model %s not run on %ld frames: the second's newest answer read |yaw| >= "
                    "%.0f deg (--second-alone-from-yaw)\n",
                    loop.model.spec().name.c_str(), counts.first_set_aside,
                    static_cast<double>(loop.options.second_alone_from_yaw));
    if (loop.second_worker && !counts.second_latency_ms.empty())
        std::printf("hkf-estimator: second model %s's capture->publish, where it goes (p50 / p99 ms): until it was "
                    "asked (the face, the first model) %.1f / %.1f, waiting for the worker %.1f / %.1f, its inference "
                    "%.1f / %.1f\n",
                    loop.second->spec().name.c_str(), percentile(counts.second_before_ms, 0.5),
                    percentile(counts.second_before_ms, 0.99), percentile(counts.second_waited_ms, 0.5),
                    percentile(counts.second_waited_ms, 0.99), percentile(loop.second_worker->inference_ms(), 0.5),
                    percentile(loop.second_worker->inference_ms(), 0.99));
    if (!capture_hung && loop.source.skipped_images() > 0)
        std::printf("hkf-estimator: %ld images of the folder could not be read; skipped\n", loop.source.skipped_images());
    if (loop.video.resized() > 0)
        std::printf("hkf-estimator: %ld frames of another size than the first were scaled to it in %s\n",
                    loop.video.resized(), loop.options.annotate_path.c_str());
    if (counts.publish_failures > 0)
        std::printf("hkf-estimator: %ld measurements could not be published on %s\n", counts.publish_failures,
                    loop.options.channel.c_str());
}

// The frame's measurement on the channel (a failure counted, and said the first time).
void publish_measurement(FrameLoop &loop, const hkf::head_pose_measurement_t &m)
{
    std::lock_guard<std::mutex> lock(loop.lcm_mutex);
    if (loop.lcm.publish(loop.options.channel, &m) != 0) {
        if (loop.counts.publish_failures++ == 0)
            std::fprintf(stderr, "hkf-estimator: publishing on %s failed (counted)\n", loop.options.channel.c_str());
    } else {
        ++loop.counts.published;
    }
}

// The frame drawn with its face, pose and the latest filtered pose, into the --annotate video and the window.
void annotate(FrameLoop &loop, const Frame &frame, const std::optional<Face> &face, const HeadPose &pose)
{
    const cv::Mat image = annotated_frame(frame.image, face, pose, loop.filtered);
    if (!loop.options.annotate_path.empty()) loop.video.write(image, loop.source.fps());
    if (loop.show) {
        cv::imshow("hkf-estimator", image);
        if (cv::waitKey(1) == 27) stop_requested = true;
    }
}

// One frame: the face tracked, the pose estimated and published, the second model asked where the first
// is unsure, the frame counted and annotated.
void process_frame(FrameLoop &loop, const Frame &frame)
{
    const int64_t taken = wall_utime();
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<Face> face = loop.tracker.track(frame.image, frame.utime);
    const std::optional<Face> tracked = face;
    const bool set_aside = tracked && loop.second_worker && loop.drop_old &&
                           first_model_set_aside(loop.second_worker->newest_answer(), frame.utime,
                                                 loop.options.second_alone_from_yaw);
    std::optional<HeadPose> estimate = face && !set_aside ? loop.model.estimate(frame.image, *face) : std::nullopt;
    if (!estimate) face.reset();  // the pose model saw no face there either, or was not run (set aside)
    loop.counts.first_set_aside += set_aside;
    const HeadPose pose = estimate.value_or(HeadPose{});
    const double inference = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const hkf::head_pose_measurement_t m =
        measurement_message(frame.utime, loop.seq++, loop.model.spec().name, face, pose, inference);
    publish_measurement(loop, m);
    if (loop.second_worker && tracked && (!estimate || std::fabs(estimate->yaw) >= loop.options.second_from_yaw)) {
        // after the first model's message, so that the node has the frame when the second's comes
        loop.second_worker->submit(SecondModelJob{frame.image, *tracked, m.utime, m.seq, taken}, loop.drop_old);
    }
    // from the frame being available (a camera's capture) to its publish
    loop.counts.latency_ms.push_back(static_cast<double>(wall_utime() - (loop.source.live() ? frame.utime : taken)) / 1000.0);
    loop.counts.inference_ms.push_back(inference);
    ++loop.counts.frames;
    loop.counts.with_face += face.has_value() || set_aside;  // a frame left to the second model has one too
    const bool annotating = !loop.options.annotate_path.empty() || loop.show;
    if (annotating || loop.pictures) {
        std::lock_guard<std::mutex> lock(loop.lcm_mutex);
        loop.lcm.handleTimeout(0);  // filtered poses (for the annotation) and a view's requests that have arrived
    }
    if (loop.pictures && loop.pictures->due())
        loop.pictures->offer(PictureFrame{frame.image, set_aside ? tracked : face,
                                          face ? loop.model.landmarks() : std::vector<cv::Point2f>{}, estimate, m.utime,
                                          m.seq});
    if (annotating) annotate(loop, frame, face, pose);
    if (loop.counts.frames % 100 == 0)
        std::fprintf(stderr, "hkf-estimator: %ld frames, %ld with a face\n", loop.counts.frames, loop.counts.with_face);
    if (loop.second_worker && !loop.second_worker->error().empty()) throw EstimatorError(loop.second_worker->error());
}

// The frames as they come, until the source ends or a stop is asked for: "", or what stopped the loop
// (the capture thread is stopped and the video closed by the caller, as always).
std::string frame_loop(FrameLoop &loop, LatestFrame &slot, StallWatch &stall)
{
    try {
        for (;;) {
            bool ended = false;
            auto frame = slot.take(std::chrono::milliseconds(100), ended);
            if (ended || stop_requested) break;
            if (!frame) {
                stall.no_frame(loop.source);
                continue;
            }
            stall.frame();
            process_frame(loop, *frame);
        }
    } catch (const std::exception &e) {
        stop_requested = true;
        return e.what();
    }
    return "";
}

// 1 (said on stderr) when a model gave NaN or infinite outputs: a healthy network never does.
int damaged_models(const HeadPoseEstimator &model, const HeadPoseEstimator *second)
{
    int damaged = 0;
    for (const HeadPoseEstimator *m : {&model, second}) {
        if (m == nullptr || m->non_finite_outputs() == 0) continue;
        std::fprintf(stderr, "hkf-estimator: the model %s gave NaN or infinite outputs on %ld faces (no pose there): "
                     "its weights are damaged? (%s)\n", m->spec().name.c_str(), m->non_finite_outputs(),
                     kModelsHint.c_str());
        damaged = 1;
    }
    return damaged;
}

// 0 (also for a stop asked for before the first frame: Ctrl-C as the models load); 1 for no frame, a
// failure or a publish that failed; kExitSourceEnded for a camera or
// stream that ended by itself; kExitDamagedFile for a file that ended well short of its
// frame count (the decoder gave up on damage; the count can be approximate, hence the margin).
int exit_status(const RunCounts &counts, bool failed, const FrameSource &source, const PipelineOptions &options)
{
    int status = counts.frames > 0 || stop_requested ? 0 : 1;
    if (counts.frames == 0 && !failed && !stop_requested)
        std::fprintf(stderr, "hkf-estimator: %s gave no frame: %s\n", source.description().c_str(),
                     source.expected_frames() == 0 ? "it holds none (an empty video or folder)"
                                                    : "none of its frames could be decoded");
    if (failed || counts.publish_failures > 0) status = 1;
    if (!failed && !stop_requested && source.live()) {
        std::fprintf(stderr, "hkf-estimator: %s stopped delivering frames (unplugged?) after %ld frames\n",
                     source.description().c_str(), counts.frames);
        status = kExitSourceEnded;
    }
    const int64_t expected = source.expected_frames(), read = source.frames_read();
    if (!failed && !stop_requested && !source.live() && options.max_frames == 0 && expected > 0 &&
        read < expected - std::max<int64_t>(5, expected / 50)) {
        std::fprintf(stderr, "hkf-estimator: %s ended after %lld of its %lld frames: the rest could not be decoded "
                     "(a damaged file?)\n", source.description().c_str(), static_cast<long long>(read),
                     static_cast<long long>(expected));
        status = kExitDamagedFile;
    }
    return status;
}


// The LCM provider of the run's output (a file:// URL checked, after '' has become $LCM_DEFAULT_URL as LCM
// reads it: never the source, a file in a source folder or the video, never a named pipe; its log is checked
// at the end through log_file).
std::unique_ptr<lcm::LCM> open_output(const PipelineOptions &options, lcm_file_url_t &log_file)
{
    const char *keep[] = {options.source.c_str(), options.annotate_path.c_str()};
    if (lcm_file_url_check(options.lcm_url.c_str(), "output", keep, options.annotate_path.empty() ? 1 : 2,
                           "hkf-estimator", &log_file) != 0)
        throw EstimatorError("--lcm-url " + std::string(lcm_url_resolve(options.lcm_url.c_str())) + " refused");
    auto lcm = std::make_unique<lcm::LCM>(lcm_url_resolve(options.lcm_url.c_str()));  // '': $LCM_DEFAULT_URL, as checked
    if (!lcm->good()) throw EstimatorError("cannot open LCM provider " + options.lcm_url);
    return lcm;
}

// --show where there is a display (said when there is none).
bool can_show(const PipelineOptions &options)
{
    if (options.show && std::getenv("DISPLAY") == nullptr) {
        std::fprintf(stderr, "hkf-estimator: --show needs a display (DISPLAY is not set); no window\n");
        return false;
    }
    return options.show;
}

// After the loop: the status from how it went, the damaged models, the log read back and the video checked.
int finish_status(const FrameLoop &loop, bool failed, const lcm_file_url_t &log_file)
{
    int status = exit_status(loop.counts, failed, loop.source, loop.options);
    if (damaged_models(loop.model, loop.second)) status = 1;
    if (lcm_file_url_verify(&log_file, loop.counts.published, "hkf-estimator") != 0) status = 1;
    if (const std::string problem = loop.video.problem(); !problem.empty()) {
        std::fprintf(stderr, "hkf-estimator: %s\n", problem.c_str());
        status = 1;
    }
    return status;
}

}  // namespace

int run_pipeline(HeadPoseEstimator &model, TrackerDetectors detectors, const PipelineOptions &options,
                 HeadPoseEstimator *second)
{
    FrameSource source(options.source, options.fps_for_images);
    lcm_file_url_t log_file;
    std::unique_ptr<lcm::LCM> lcm_owner = open_output(options, log_file);
    FilteredPose filtered;
    if (!options.annotate_path.empty() || options.show)
        lcm_subscribe(lcm_owner->getUnderlyingLCM(), options.filtered_channel.c_str(), on_filtered_pose, &filtered);
    FaceTracker tracker(detectors, options.tracker);
    AnnotatedVideo video(options.annotate_path);
    const bool show = can_show(options);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::signal(SIGHUP, on_signal);  // the terminal closed: stop with the summary and a whole --annotate video
    warm_up(detectors);

    const bool drop_old = source.live() || options.realtime;
    LatestFrame slot;
    Capture capture(source, slot, options, drop_old, stop_requested);
    std::fprintf(stderr, "hkf-estimator: %s -> %s on %s (model %s)\n", source.description().c_str(), options.channel.c_str(),
                 options.lcm_url.c_str(), model.spec().name.c_str());
    std::mutex lcm_mutex;
    RunCounts counts;
    FrameLoop loop{options, model, second, source, *lcm_owner, lcm_mutex, counts, tracker, video, filtered, show, drop_old,
                   nullptr, nullptr};
    loop.second_worker = start_second_model(loop);
    if (std::strncmp(lcm_url_resolve(options.lcm_url.c_str()), "file://", 7) != 0)
        loop.pictures = std::make_unique<CameraPictures>(*lcm_owner, lcm_mutex, "HEAD_POSE_PICTURE",
                                                         "HEAD_POSE_PICTURE_REQUEST");
    const auto started = std::chrono::steady_clock::now();
    StallWatch stall;
    const std::string loop_error = frame_loop(loop, slot, stall);
    if (loop.second_worker) loop.second_worker->stop();  // its frames in hand are measured and published
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    video.close();  // the annotated video is whole, however the run ends
    const bool capture_hung = !capture.stop();
    if (capture.failed()) std::fprintf(stderr, "hkf-estimator: %s\n", capture.error().c_str());
    if (!loop_error.empty()) std::fprintf(stderr, "hkf-estimator: stopped: %s\n", loop_error.c_str());
    {
        std::lock_guard<std::mutex> lock(lcm_mutex);
        print_summary(loop, seconds, slot, stall, capture_hung);
    }
    const bool failed = capture.failed() || !loop_error.empty();
    loop.second_worker.reset();  // it publishes on lcm: gone first
    loop.pictures.reset();
    lcm_owner.reset();           // closes a file:// log, which is then read back
    const int status = finish_status(loop, failed, log_file);
    if (capture_hung) {
        std::fprintf(stderr, "hkf-estimator: %s is not responding; leaving it\n", source.description().c_str());
        std::fflush(stdout);
        std::fflush(stderr);
        std::_Exit(status);  // the summary is out and the video closed; the hung thread cannot be joined
    }
    return status;
}

}  // namespace hkf_estimator
