// pipeline.cpp - see pipeline.hpp.
#include "pipeline.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/highgui.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "frame_source.hpp"
#include "hkf/head_pose_measurement_t.hpp"
#include "hkf/head_pose_t.hpp"
#include "pose_drawing.hpp"
#include "second_model.hpp"

namespace hkf_estimator {
namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int) { stop_requested = true; }

// The one-frame slot between the capture and the processing thread.
class LatestFrame {
public:
    // Puts a frame in. When the slot is full: with drop_old, the old frame is
    // replaced (and counted); without, the call waits until it is taken.
    void put(Frame frame, bool drop_old)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        if (!drop_old) taken_.wait(lock, [&] { return !full_ || closed_; });
        if (full_) ++dropped_;
        frame_ = std::move(frame);
        full_ = true;
        arrived_.notify_one();
    }
    // The newest frame, waiting up to `timeout`; nullopt when none came in that
    // time, or (ended = true) once the source has ended and the slot is empty.
    std::optional<Frame> take(std::chrono::milliseconds timeout, bool &ended)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        arrived_.wait_for(lock, timeout, [&] { return full_ || closed_; });
        ended = !full_ && closed_;
        if (!full_) return std::nullopt;
        full_ = false;
        taken_.notify_one();
        return std::move(frame_);
    }
    void close()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        closed_ = true;
        arrived_.notify_all();
        taken_.notify_all();
    }
    long dropped() const
    {
        std::lock_guard<std::mutex> lock(mutex_);
        return dropped_;
    }

private:
    mutable std::mutex mutex_;
    std::condition_variable arrived_, taken_;
    Frame frame_;
    bool full_ = false, closed_ = false;
    long dropped_ = 0;
};

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

}  // namespace

int run_pipeline(HeadPoseEstimator &model, TrackerDetectors detectors, const PipelineOptions &options,
                 HeadPoseEstimator *second)
{
    FrameSource source(options.source, options.fps_for_images);
    lcm::LCM lcm(options.lcm_url);
    if (!lcm.good()) throw EstimatorError("cannot open LCM provider " + options.lcm_url);
    FilteredPose filtered;
    if (!options.annotate_path.empty() || options.show)
        lcm_subscribe(lcm.getUnderlyingLCM(), options.filtered_channel.c_str(), on_filtered_pose, &filtered);
    FaceTracker tracker(detectors, options.tracker);
    cv::VideoWriter writer;
    cv::Size writer_size;
    bool show = options.show;
    if (show && std::getenv("DISPLAY") == nullptr) {
        std::fprintf(stderr, "hkf-estimator: --show needs a display (DISPLAY is not set); no window\n");
        show = false;
    }
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::signal(SIGHUP, on_signal);  // the terminal closed: stop with the summary and a whole --annotate video

    // OpenCV DNN's first forward pass of a network costs several of the next: spent
    // here, before capture starts, not on the first frames of a camera
    const cv::Mat blank(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
    detectors.search->detect(blank);
    if (detectors.region != detectors.search) detectors.region->detect(blank);

    const bool drop_old = source.live() || options.realtime;
    LatestFrame slot;
    std::atomic<bool> capture_failed{false}, capture_done{false};
    std::string capture_error;
    std::thread capture([&] {
        try {
            const int64_t start = wall_utime();
            for (long n = 0; !stop_requested && (options.max_frames == 0 || n < options.max_frames); ++n) {
                Frame frame;
                if (!source.read(frame)) break;
                if (options.realtime && !source.live()) {  // pace a file at its frame rate
                    const int64_t due = start + static_cast<int64_t>(1e6 * static_cast<double>(frame.index) / source.fps());
                    std::this_thread::sleep_for(std::chrono::microseconds(std::max<int64_t>(0, due - wall_utime())));
                    frame.utime = wall_utime();
                }
                slot.put(std::move(frame), drop_old);
            }
        } catch (const std::exception &e) {  // EstimatorError, or OpenCV's own on a broken source
            capture_error = e.what();
            capture_failed = true;
        }
        slot.close();
        capture_done = true;
    });

    std::fprintf(stderr, "hkf-estimator: %s -> %s on %s (model %s)\n", source.description().c_str(), options.channel.c_str(),
                 options.lcm_url.c_str(), model.spec().name.c_str());
    // LCM is published to from this thread and the second model's; one at a time
    std::mutex lcm_mutex;
    long publish_failures = 0;  // under lcm_mutex
    std::vector<double> second_latency_ms;  // capture -> publish of the second model's measurements
    std::unique_ptr<SecondModelWorker> second_worker;
    if (second != nullptr) {
        std::fprintf(stderr, "hkf-estimator: second model %s where %s finds no pose or |yaw| >= %.0f deg\n",
                     second->spec().name.c_str(), model.spec().name.c_str(), static_cast<double>(options.second_from_yaw));
        second_worker = std::make_unique<SecondModelWorker>(*second, [&](const SecondModelResult &r) {
            std::optional<Face> face;
            if (r.pose) face = r.job.face;
            const hkf::head_pose_measurement_t m = measurement_message(r.job.utime, r.job.seq, second->spec().name, face,
                                                                       r.pose.value_or(HeadPose{}), r.inference_ms);
            std::lock_guard<std::mutex> lock(lcm_mutex);
            if (lcm.publish(options.channel, &m) != 0) ++publish_failures;
            second_latency_ms.push_back(static_cast<double>(wall_utime() - (source.live() ? r.job.utime : r.job.taken_utime)) /
                                        1000.0);
        });
    }
    long frames = 0, with_face = 0;
    std::vector<double> latency_ms, inference_ms;
    const auto started = std::chrono::steady_clock::now();
    int64_t seq = 0;
    // A source that stops delivering frames (a camera unplugged or hung, a
    // stream stalled) is reported after kStallWarning; the loop keeps waiting
    // for it and still stops promptly on SIGINT / SIGTERM.
    constexpr auto kStallWarning = std::chrono::seconds(2);
    auto last_frame_time = std::chrono::steady_clock::now();
    bool stalled = false;
    long stalls = 0, resized = 0;
    std::string loop_error;  // what stopped the frame loop, if anything did
    try {
        for (;;) {
            bool ended = false;
            auto frame = slot.take(std::chrono::milliseconds(100), ended);
            if (ended || stop_requested) break;
            const auto now = std::chrono::steady_clock::now();
            if (!frame) {
                if (!stalled && now - last_frame_time >= kStallWarning) {
                    stalled = true;
                    ++stalls;
                    std::fprintf(stderr, "hkf-estimator: no frame from %s for %.1f s (camera unplugged or stalled?); waiting\n",
                                 source.description().c_str(), std::chrono::duration<double>(now - last_frame_time).count());
                }
                continue;
            }
            if (stalled) {
                std::fprintf(stderr, "hkf-estimator: frames again after %.1f s\n",
                             std::chrono::duration<double>(now - last_frame_time).count());
                stalled = false;
            }
            last_frame_time = now;
            const int64_t taken = wall_utime();
            const auto t0 = std::chrono::steady_clock::now();
            std::optional<Face> face = tracker.track(frame->image, frame->utime);
            const std::optional<Face> tracked = face;
            std::optional<HeadPose> estimate = face ? model.estimate(frame->image, *face) : std::nullopt;
            if (!estimate) face.reset();  // the pose model saw no face there either
            const HeadPose pose = estimate.value_or(HeadPose{});
            const double inference = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

            const hkf::head_pose_measurement_t m =
                measurement_message(frame->utime, seq++, model.spec().name, face, pose, inference);
            {
                std::lock_guard<std::mutex> lock(lcm_mutex);
                if (lcm.publish(options.channel, &m) != 0 && publish_failures++ == 0)
                    std::fprintf(stderr, "hkf-estimator: publishing on %s failed (counted)\n", options.channel.c_str());
            }
            if (second_worker && tracked && (!estimate || std::fabs(estimate->yaw) >= options.second_from_yaw)) {
                // after the first model's message, so that the node has the frame when the second's comes
                second_worker->submit(SecondModelJob{frame->image, *tracked, m.utime, m.seq, taken}, drop_old);
            }
            // from the frame being available (a camera's capture) to its publish
            latency_ms.push_back(static_cast<double>(wall_utime() - (source.live() ? frame->utime : taken)) / 1000.0);
            inference_ms.push_back(inference);
            ++frames;
            with_face += face.has_value();

            if (!options.annotate_path.empty() || show) {
                {
                    std::lock_guard<std::mutex> lock(lcm_mutex);
                    lcm.handleTimeout(0);  // filtered poses that have arrived
                }
                cv::Mat image = frame->image.clone();
                if (face) {
                    draw_face(image, *face);
                    const cv::Point2f c(face->box.x + face->box.width / 2, face->box.y + face->box.height / 2);
                    draw_pose_axes(image, pose, c, 0.8f * face->box.width, 2);
                    char text[96];
                    std::snprintf(text, sizeof text, "raw p %.1f y %.1f r %.1f", pose.pitch, pose.yaw, pose.roll);
                    cv::putText(image, text, {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 255, 255), 2);
                    if (pose.has_position) {
                        std::snprintf(text, sizeof text, "head x %.1f y %.1f z %.1f cm", pose.position.x, pose.position.y,
                                      pose.position.z);
                        cv::putText(image, text, {10, 75}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 255, 255), 2);
                    }
                    std::lock_guard<std::mutex> lock(filtered.mutex);
                    if (filtered.have) {
                        draw_pose_axes(image, filtered.pose, c, 0.8f * face->box.width, 5);
                        std::snprintf(text, sizeof text, "filtered p %.1f y %.1f r %.1f", filtered.pose.pitch, filtered.pose.yaw,
                                      filtered.pose.roll);
                        cv::putText(image, text, {10, 50}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 2);
                    }
                } else {
                    cv::putText(image, "no face", {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 255), 2);
                }
                if (!options.annotate_path.empty()) {
                    if (!writer.isOpened()) {
                        writer_size = image.size();
                        if (!writer.open(options.annotate_path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), source.fps(), writer_size))
                            throw EstimatorError("cannot write the video " + options.annotate_path);
                    }
                    if (image.size() != writer_size) {  // a source that changes size: the video keeps its first size
                        cv::Mat scaled;
                        cv::resize(image, scaled, writer_size, 0, 0, cv::INTER_AREA);
                        image = scaled;
                        ++resized;
                    }
                    writer.write(image);
                }
                if (show) {
                    cv::imshow("hkf-estimator", image);
                    if (cv::waitKey(1) == 27) stop_requested = true;
                }
            }
            if (frames % 100 == 0)
                std::fprintf(stderr, "hkf-estimator: %ld frames, %ld with a face\n", frames, with_face);
            if (second_worker && !second_worker->error().empty()) throw EstimatorError(second_worker->error());
        }
    } catch (const std::exception &e) {  // the capture thread is stopped and the video closed below, as always
        loop_error = e.what();
        stop_requested = true;
    }
    if (second_worker) second_worker->stop();  // its frames in hand are measured and published
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (writer.isOpened()) writer.release();  // the annotated video is whole, however the run ends
    // A capture thread blocked inside the source (a hung camera or stream) cannot
    // be interrupted: give it a moment, then leave without it (see below).
    slot.close();  // a capture waiting to hand over a frame gives up
    const auto stop_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (!capture_done && std::chrono::steady_clock::now() < stop_deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const bool capture_hung = !capture_done;
    if (!capture_hung) capture.join();
    if (capture_failed) std::fprintf(stderr, "hkf-estimator: %s\n", capture_error.c_str());
    if (!loop_error.empty()) std::fprintf(stderr, "hkf-estimator: stopped: %s\n", loop_error.c_str());
    std::printf("hkf-estimator: %ld frames, %ld with a face, %.1f fps; capture->publish ms p50 %.1f p99 %.1f; "
                "inference ms p50 %.1f; %ld dropped; %ld full-frame face searches; %ld stalls of the source\n",
                frames, with_face, seconds > 0 ? static_cast<double>(frames) / seconds : 0.0, percentile(latency_ms, 0.5),
                percentile(latency_ms, 0.99), percentile(inference_ms, 0.5), slot.dropped(), tracker.full_frame_searches(),
                stalls);
    if (second_worker)
        std::printf("hkf-estimator: second model %s: %ld frames asked for, %ld measured, %ld skipped (it was busy); "
                    "capture->publish ms p50 %.1f p99 %.1f; inference ms p50 %.1f\n",
                    second->spec().name.c_str(), second_worker->asked(), second_worker->done(), second_worker->skipped(),
                    percentile(second_latency_ms, 0.5), percentile(second_latency_ms, 0.99),
                    percentile(second_worker->inference_ms(), 0.5));
    if (!capture_hung && source.skipped_images() > 0)
        std::printf("hkf-estimator: %ld images of the folder could not be read; skipped\n", source.skipped_images());
    if (resized > 0)
        std::printf("hkf-estimator: %ld frames of another size than the first were scaled to it in %s\n", resized,
                    options.annotate_path.c_str());
    {
        std::lock_guard<std::mutex> lock(lcm_mutex);
        if (publish_failures > 0)
            std::printf("hkf-estimator: %ld measurements could not be published on %s\n", publish_failures,
                        options.channel.c_str());
    }
    int status = frames > 0 ? 0 : 1;
    const bool failed = capture_failed || !loop_error.empty();
    if (failed || publish_failures > 0) status = 1;
    if (!failed && !stop_requested && source.live()) {  // a camera or stream that ends by itself has failed
        std::fprintf(stderr, "hkf-estimator: %s stopped delivering frames (unplugged?) after %ld frames\n",
                     source.description().c_str(), frames);
        status = kExitSourceEnded;
    }
    // a file that ends well short of its container's frame count: the decoder
    // gave up on damage (the count can be approximate, hence the margin)
    const int64_t expected = source.expected_frames(), read = source.frames_read();
    if (!failed && !stop_requested && !source.live() && options.max_frames == 0 && expected > 0 &&
        read < expected - std::max<int64_t>(5, expected / 50)) {
        std::fprintf(stderr, "hkf-estimator: %s ended after %lld of its %lld frames: the rest could not be decoded "
                     "(a damaged file?)\n", source.description().c_str(), static_cast<long long>(read),
                     static_cast<long long>(expected));
        status = kExitDamagedFile;
    }
    if (capture_hung) {
        std::fprintf(stderr, "hkf-estimator: %s is not responding; leaving it\n", source.description().c_str());
        std::fflush(stdout);
        std::fflush(stderr);
        std::_Exit(status);  // the summary is out and the video closed; the hung thread cannot be joined
    }
    return status;
}

}  // namespace hkf_estimator
