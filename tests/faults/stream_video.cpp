// stream_video - a test's stand-in for a camera: decodes a real video and
// writes its frames as a live YUV4MPEG2 stream (to a named pipe that
// hkf-estimator reads), at the video's frame rate, with the faults a camera
// has: a stall (no frames for a while, then frames again), a hang (no more
// frames, the pipe left open), an unplug (the pipe closed mid-video).
// usage: stream_video VIDEO OUT [--frames N] [--stall-after N --stall-seconds S] [--hang-after N]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

int main(int argc, char **argv)
{
    if (argc < 3 || std::strcmp(argv[1], "--help") == 0) {
        std::printf("usage: stream_video VIDEO OUT [--frames N] [--stall-after N --stall-seconds S] [--hang-after N]\n"
                    "Writes VIDEO's frames to OUT (a named pipe) as a live YUV4MPEG2 stream at its frame rate.\n");
        return argc < 3 ? 2 : 0;
    }
    long frames = -1, stall_after = -1, hang_after = -1;
    double stall_seconds = 0;
    for (int i = 3; i + 1 < argc; i += 2) {
        const std::string option = argv[i];
        char *end = nullptr;
        const double value = std::strtod(argv[i + 1], &end);
        if (end == argv[i + 1] || *end != '\0' || !(value >= 0 && value <= 1e6)) {
            std::fprintf(stderr, "stream_video: %s wants a number from 0 to 1e6, not '%s'\n", option.c_str(), argv[i + 1]);
            return 2;
        }
        if (option == "--frames") frames = static_cast<long>(value);
        else if (option == "--stall-after") stall_after = static_cast<long>(value);
        else if (option == "--stall-seconds") stall_seconds = value;
        else if (option == "--hang-after") hang_after = static_cast<long>(value);
        else {
            std::fprintf(stderr, "stream_video: unknown option %s\n", option.c_str());
            return 2;
        }
    }
    cv::VideoCapture video(argv[1], cv::CAP_FFMPEG);
    if (!video.isOpened()) {
        std::fprintf(stderr, "stream_video: cannot read %s\n", argv[1]);
        return 1;
    }
    const double fps = video.get(cv::CAP_PROP_FPS) > 0 ? video.get(cv::CAP_PROP_FPS) : 30.0;
    FILE *out = std::fopen(argv[2], "wb");
    if (out == nullptr) {
        std::fprintf(stderr, "stream_video: cannot write %s\n", argv[2]);
        return 1;
    }
    cv::Mat bgr, yuv;
    long n = 0;
    const auto start = std::chrono::steady_clock::now();
    auto due = start;
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / fps));
    while ((frames < 0 || n < frames) && video.read(bgr)) {
        if (bgr.cols % 2 || bgr.rows % 2) bgr = bgr(cv::Rect(0, 0, bgr.cols & ~1, bgr.rows & ~1)).clone();
        if (n == 0)
            std::fprintf(out, "YUV4MPEG2 W%d H%d F%ld:1000 Ip A1:1 C420jpeg\n", bgr.cols, bgr.rows, std::lround(fps * 1000));
        if (n == hang_after) {
            std::fprintf(stderr, "stream_video: hanging after %ld frames\n", n);
            std::fflush(out);
            for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // until killed
        }
        if (n == stall_after) {
            std::fprintf(stderr, "stream_video: stalling %.1f s after %ld frames\n", stall_seconds, n);
            std::fflush(out);
            std::this_thread::sleep_for(std::chrono::duration<double>(stall_seconds));
            due = std::chrono::steady_clock::now();
        }
        cv::cvtColor(bgr, yuv, cv::COLOR_BGR2YUV_I420);
        std::fputs("FRAME\n", out);
        if (std::fwrite(yuv.data, 1, yuv.total() * yuv.elemSize(), out) != yuv.total() * yuv.elemSize()) break;  // reader gone
        std::fflush(out);
        ++n;
        due += period;
        std::this_thread::sleep_until(due);
    }
    std::fprintf(stderr, "stream_video: %ld frames written; closing the stream\n", n);
    std::fclose(out);
    return 0;
}
