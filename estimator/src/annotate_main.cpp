// hkf-annotate - draws raw and filtered head poses on the video they came from:
// the face box, the raw pose's axes (thin) and the filtered pose's (thick),
// both as numbers, and a strip chart of the last seconds of pitch, yaw and roll
// (raw dots, filtered lines). For the offline demo, where the filter runs after
// the estimator, so the estimator's own --annotate can show only the raw pose.
//
// Frames are matched to raw poses by the estimator's frame counter (seq = frame
// index for a file read in full), raw poses to filtered ones by capture time
// (head_pose_t.utime == head_pose_measurement_t.utime, not extrapolated).
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "opencv_environment.hpp"
#include "pose_drawing.hpp"
#include "written_video.hpp"

#include "lcm_log_reader.h"
#include "message_decode.h"
#include "safe_files.h"

namespace {

const char *const usage =
    "usage: hkf-annotate VIDEO RAW.lcmlog FILTERED.lcmlog OUT.mp4 [--trace-seconds S] [--still N OUT.png]\n"
    "  Draws the raw poses (HEAD_POSE_RAW in RAW.lcmlog, from hkf-estimator) and the filtered\n"
    "  ones (HEAD_POSE in FILTERED.lcmlog, from hkf-filter --offline) on VIDEO: face box, raw\n"
    "  axes thin, filtered axes thick, both as numbers, and a strip chart of the last S seconds\n"
    "  (default 4) of pitch, yaw, roll: raw dots, filtered lines.\n"
    "  --still N OUT.png   also write annotated frame N (from 0) as a picture\n"
    "  --raw-channel NAME, --filtered-channel NAME   other channels (defaults above)\n"
    "  --help, --version   this text; the version\n"
    "  exit 0: written; 1: an input is missing, unreadable or has no poses; 2: bad arguments\n";

struct Options {
    std::string video, raw_log, filtered_log, out;
    std::string raw_channel = "HEAD_POSE_RAW", filtered_channel = "HEAD_POSE";
    double trace_seconds = 4.0;
    long still_index = -1;  // a frame to write as a picture too (-1: none)
    std::string still_path;
};

int fail(const std::string &message)
{
    std::fprintf(stderr, "hkf-annotate: %s\n", message.c_str());
    return 1;
}

// A message of hkf 0.2, or of hkf 0.1 (no position, which stays 0: message_decode.h); false when it
// is neither. The measurement's model id is not kept.
bool decode_message(hkf_head_pose_measurement_t &m, const void *data, int size)
{
    if (message_decode_measurement(data, size, &m) != 0) return false;
    hkf_head_pose_measurement_t_decode_cleanup(&m);
    m.model = nullptr;
    return true;
}

bool decode_message(hkf_head_pose_t &p, const void *data, int size) { return message_decode_pose(data, size, &p) == 0; }

// Every event of `channel` in the log decoded as T; false (with `error`) if the file cannot be read.
template <typename T>
bool read_channel(const std::string &path, const std::string &channel, std::vector<T> &out, std::string &error)
{
    char reason[600];
    FILE *f = safe_open_input(path.c_str(), reason, sizeof reason);  // a regular file: a named pipe would block
    if (f == nullptr) {
        error = reason;
        return false;
    }
    lcm_log_reader_t reader;
    if (lcm_log_reader_open(&reader, f) != 0) {
        std::fclose(f);
        error = path + " is not a seekable file";
        return false;
    }
    static char data[1 << 16];
    lcm_log_event_t event;
    long undecodable = 0;
    while (lcm_log_reader_next(&reader, &event, data, sizeof data) == 1) {
        if (!event.data_read || channel != event.channel) continue;
        T message{};
        if (!decode_message(message, data, event.datalen)) {
            ++undecodable;
            continue;
        }
        out.push_back(message);
    }
    if (reader.skipped > 0 || lcm_log_reader_cut(&reader) > 0 || undecodable > 0)
        std::fprintf(stderr, "hkf-annotate: %s: %ld damaged bytes skipped, %ld cut off at the end, %ld %s messages "
                     "that do not decode\n", path.c_str(), reader.skipped, lcm_log_reader_cut(&reader), undecodable,
                     channel.c_str());
    std::fclose(f);
    return true;
}

bool finite(const hkf_estimator::HeadPose &p) { return std::isfinite(p.pitch) && std::isfinite(p.yaw) && std::isfinite(p.roll); }

// One frame's poses for the strip chart.
struct TracePoint {
    double t;
    std::optional<hkf_estimator::HeadPose> raw, filtered;
};

// --trace-seconds, --raw-channel or --filtered-channel and its value into o; false (said) when the value is bad.
bool read_value_option(const std::string &arg, const std::string &value, Options &o)
{
    if (arg == "--raw-channel") {
        o.raw_channel = value;
    } else if (arg == "--filtered-channel") {
        o.filtered_channel = value;
    } else {
        char *end = nullptr;
        o.trace_seconds = std::strtod(value.c_str(), &end);
        if (end == value.c_str() || *end != '\0' || !(o.trace_seconds > 0.0 && o.trace_seconds <= 60.0)) {
            std::fprintf(stderr, "hkf-annotate: --trace-seconds wants a number in (0, 60], not '%s'\n", value.c_str());
            return false;
        }
    }
    return true;
}

int parse(int argc, char **argv, Options &o)
{
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::fputs(usage, stdout);
            return 1;
        }
        if (arg == "--version") {
            std::printf("hkf-annotate %s\n", HKF_VERSION);
            return 1;
        }
        if (arg == "--still") {
            if (i + 2 >= argc) {
                std::fprintf(stderr, "hkf-annotate: --still needs a frame index and a file\n%s", usage);
                return 2;
            }
            char *end = nullptr;
            o.still_index = std::strtol(argv[i + 1], &end, 10);
            if (end == argv[i + 1] || *end != '\0' || o.still_index < 0) {
                std::fprintf(stderr, "hkf-annotate: --still wants a frame index >= 0, not '%s'\n", argv[i + 1]);
                return 2;
            }
            o.still_path = argv[i + 2];
            i += 2;
        } else if (arg == "--trace-seconds" || arg == "--raw-channel" || arg == "--filtered-channel") {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "hkf-annotate: %s needs a value\n%s", arg.c_str(), usage);
                return 2;
            }
            if (!read_value_option(arg, argv[++i], o)) return 2;
        } else if (!arg.empty() && arg[0] == '-') {
            std::fprintf(stderr, "hkf-annotate: unknown option '%s'\n%s", arg.c_str(), usage);
            return 2;
        } else {
            positional.push_back(arg);
        }
    }
    if (positional.size() != 4) {
        std::fprintf(stderr, "hkf-annotate: wants VIDEO RAW.lcmlog FILTERED.lcmlog OUT.mp4\n%s", usage);
        return 2;
    }
    o.video = positional[0];
    o.raw_log = positional[1];
    o.filtered_log = positional[2];
    o.out = positional[3];
    return 0;
}

std::atomic<bool> stop_requested{false};
extern "C" void on_stop_signal(int) { stop_requested = true; }

int annotate(const Options &o);

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    safe_files_fail_writes_past_size_limit();  // a file-size limit: a reported write error, not SIGXFSZ
    switch (parse(argc, argv, o)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }
    if (*hkf_estimator::opencv_environment_problem() != '\0') {  // settled before OpenCV loaded (opencv_environment.hpp)
        std::fprintf(stderr, "hkf-annotate: %s\n", hkf_estimator::opencv_environment_problem());
        return 2;
    }
    for (const std::string *input : {&o.video, &o.raw_log, &o.filtered_log}) safe_note_read(input->c_str());
    for (const std::string *output : {&o.out, &o.still_path}) {  // never an input, under any name
        char reason[2 * PATH_MAX + 200];
        if (!output->empty() && safe_output_problem(output->c_str(), reason, sizeof reason) != 0) return fail(reason);
    }
    // SIGINT / SIGTERM / SIGHUP: stop between frames with the video closed (playable) and exit 1
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    std::signal(SIGHUP, on_stop_signal);
    try {
        return annotate(o);
    } catch (const std::exception &e) {
        return fail(e.what());
    }
}

namespace {

// A message's angles and, where measured and finite, its position.
template <typename Message>
hkf_estimator::HeadPose pose_of(const Message &m)
{
    hkf_estimator::HeadPose pose{m.pitch, m.yaw, m.roll};
    if (m.z > 0.f && std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z)) {
        pose.position = {m.x, m.y, m.z};
        pose.has_position = true;
    }
    return pose;
}

// The logs' poses, found by frame: raw by seq (the first model's, where a second one measured too),
// filtered by the raw pose's capture time (posteriors only).
struct PoseIndex {
    std::map<int64_t, const hkf_head_pose_measurement_t *> raw_by_seq;
    std::map<int64_t, const hkf_head_pose_t *> filtered_by_utime;
    long with_raw = 0, with_filtered = 0;  // frames drawn with each
};

// One frame's raw and filtered poses (those finite) and its face box, counted in the index.
TracePoint frame_point(PoseIndex &poses, int64_t seq, double t, std::optional<cv::Rect2f> &box)
{
    TracePoint point{t, std::nullopt, std::nullopt};
    const auto r = poses.raw_by_seq.find(seq);
    if (r == poses.raw_by_seq.end()) return point;
    const hkf_head_pose_measurement_t &m = *r->second;
    const hkf_estimator::HeadPose raw = pose_of(m);
    if (m.valid && finite(raw)) {
        point.raw = raw;
        box = cv::Rect2f(cv::Point2f(m.face_box[0], m.face_box[1]), cv::Point2f(m.face_box[2], m.face_box[3]));
        ++poses.with_raw;
    }
    const auto f = poses.filtered_by_utime.find(m.utime);
    if (f != poses.filtered_by_utime.end() && finite(pose_of(*f->second))) {
        point.filtered = pose_of(*f->second);
        ++poses.with_filtered;
    }
    return point;
}

// The checks after the last frame: the video written whole, the still within it, a raw pose matched.
int finish(const Options &o, long frames, const PoseIndex &poses)
{
    if (frames == 0) return fail("no frames in " + o.video);
    if (o.still_index >= frames)
        return fail("--still " + std::to_string(o.still_index) + ": the video has only " + std::to_string(frames) + " frames");
    if (const std::string problem = hkf_estimator::written_video_problem(o.out, frames); !problem.empty())
        return fail(problem);
    if (stop_requested) return fail("stopped by a signal after " + std::to_string(frames) + " frames; " + o.out + " is whole up to there");
    std::printf("hkf-annotate: %s: %ld frames, %ld with a raw pose, %ld with a filtered pose\n", o.out.c_str(), frames,
                poses.with_raw, poses.with_filtered);
    if (poses.with_raw == 0) return fail("no frame of " + o.video + " matched a raw pose (is it the video of " + o.raw_log + "?)");
    return 0;
}

int annotate(const Options &o)
{
    std::vector<hkf_head_pose_measurement_t> raws;
    std::vector<hkf_head_pose_t> filtered_poses;
    std::string error;
    if (!read_channel(o.raw_log, o.raw_channel, raws, error) ||
        !read_channel(o.filtered_log, o.filtered_channel, filtered_poses, error))
        return fail(error);
    if (raws.empty()) return fail(o.raw_log + " has no " + o.raw_channel + " messages");
    if (filtered_poses.empty()) return fail(o.filtered_log + " has no " + o.filtered_channel + " messages");
    PoseIndex poses;
    for (const auto &m : raws) poses.raw_by_seq.emplace(m.seq, &m);
    for (const auto &p : filtered_poses)
        if (!p.extrapolated) poses.filtered_by_utime[p.utime] = &p;

    cv::VideoCapture video(o.video);
    if (!video.isOpened()) return fail("cannot open video " + o.video);
    double fps = video.get(cv::CAP_PROP_FPS);
    if (!(fps > 0.0 && fps < 1000.0)) fps = 30.0;
    cv::VideoWriter writer;
    std::deque<TracePoint> trace;
    const int64_t first_seq = poses.raw_by_seq.begin()->first;
    long frames = 0;
    cv::Mat image;
    for (int64_t index = 0; !stop_requested && video.read(image) && !image.empty(); ++index) {
        const double t = static_cast<double>(index) / fps;
        std::optional<cv::Rect2f> box;
        const TracePoint point = frame_point(poses, first_seq + index, t, box);
        hkf_estimator::draw_annotation(image, box, point.raw, point.filtered);
        trace.push_back(point);
        while (!trace.empty() && trace.front().t < t - o.trace_seconds) trace.pop_front();
        std::vector<hkf_estimator::TraceSample> samples;
        for (const auto &p : trace) samples.push_back({p.t, p.raw, p.filtered});
        hkf_estimator::draw_pose_trace(image, samples, t - o.trace_seconds, t);
        if (!writer.isOpened() && !writer.open(o.out, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps, image.size()))
            return fail("cannot write video " + o.out);
        writer.write(image);
        if (index == o.still_index && !cv::imwrite(o.still_path, image)) return fail("cannot write " + o.still_path);
        ++frames;
    }
    writer.release();
    return finish(o, frames, poses);
}

}  // namespace
