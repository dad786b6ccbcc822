// opencv_environment.cpp - see opencv_environment.hpp.
#include "opencv_environment.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "frame_source.hpp"  // kMaxFramePixels

namespace hkf_estimator {

namespace {

char problem[240];  // written once, before main and before any thread

static_assert(kMaxFramePixels == 33177600, "the pixel cap's rule names it");

enum class Kind { kSize, kBoolean, kPixels, kOff };

struct Variable {
    const char *name;
    Kind kind;
};

// Every variable OpenCV 4.6 parses as it loads (a bad value aborted hkf-estimator --version), and ours.
const Variable kVariables[] = {
    {"OPENCV_IO_MAX_IMAGE_PIXELS", Kind::kPixels},
    {"OPENCV_TRACE", Kind::kOff},
    {"OPENCV_IO_MAX_IMAGE_WIDTH", Kind::kSize},
    {"OPENCV_IO_MAX_IMAGE_HEIGHT", Kind::kSize},
    {"OPENCV_IO_MAX_IMAGE_PARAMS", Kind::kSize},
    {"OPENCV_IMGCODECS_WEBP_MAX_FILE_SIZE", Kind::kSize},
    {"OPENCV_KMEANS_PARALLEL_GRANULARITY", Kind::kSize},
    {"OPENCV_OPENCL_ALIGNMENT_MEM_USE_HOST_PTR", Kind::kSize},
    {"OPENCV_THREAD_POOL_ACTIVE_WAIT_MAIN", Kind::kSize},
    {"OPENCV_THREAD_POOL_ACTIVE_WAIT_PAUSE_LIMIT", Kind::kSize},
    {"OPENCV_THREAD_POOL_ACTIVE_WAIT_THREADS_LIMIT", Kind::kSize},
    {"OPENCV_THREAD_POOL_ACTIVE_WAIT_WORKER", Kind::kSize},
    {"OPENCV_TRACE_DEPTH_OPENCV", Kind::kSize},
    {"OPENCV_TRACE_MAX_CHILDREN", Kind::kSize},
    {"OPENCV_TRACE_MAX_CHILDREN_OPENCV", Kind::kSize},
    {"OPENCV_BUFFER_AREA_ALWAYS_SAFE", Kind::kBoolean},
    {"OPENCV_DUMP_ERRORS", Kind::kBoolean},
    {"OPENCV_ENABLE_MEMALIGN", Kind::kBoolean},
    {"OPENCV_OPENCL_CACHE_CLEANUP", Kind::kBoolean},
    {"OPENCV_OPENCL_CACHE_ENABLE", Kind::kBoolean},
    {"OPENCV_OPENCL_CACHE_LOCK_ENABLE", Kind::kBoolean},
    {"OPENCV_OPENCL_CACHE_WRITE", Kind::kBoolean},
    {"OPENCV_OPENCL_DISABLE_BUFFER_RECT_OPERATIONS", Kind::kBoolean},
    {"OPENCV_OPENCL_ENABLE_MEM_USE_HOST_PTR", Kind::kBoolean},
    {"OPENCV_OPENCL_VALIDATE_BINARY_PROGRAMS", Kind::kBoolean},
    {"OPENCV_TRACE_SYNC_OPENCL", Kind::kBoolean},
    {"OPENCV_VIDEOCAPTURE_DEBUG", Kind::kBoolean},
    {"OPENCV_VIDEOIO_DEBUG", Kind::kBoolean},
    {"OPENCV_VIDEOWRITER_DEBUG", Kind::kBoolean},
};

// Digits only, at most `most`; the value into *value.
bool whole_number(const char *text, const char *end, unsigned long long most, unsigned long long *value)
{
    *value = 0;
    if (text == end) return false;
    for (const char *c = text; c != end; ++c) {
        if (*c < '0' || *c > '9') return false;
        *value = *value * 10 + static_cast<unsigned long long>(*c - '0');
        if (*value > most) return false;  // checked at each digit: no overflow
    }
    return true;
}

// OpenCV's size: digits, then nothing or KB / Kb / kb / MB / Mb / mb; kept below 2^62 bytes.
bool good_size(const char *text)
{
    const char *end = text;
    while (*end >= '0' && *end <= '9') ++end;
    unsigned long long value, scale = 1;
    if (*end != '\0') {
        if (std::strlen(end) != 2 || (end[1] != 'B' && end[1] != 'b') ||
            (end[0] != 'K' && end[0] != 'k' && end[0] != 'M' && end[0] != 'm') ||
            (end[0] == 'k' && end[1] == 'B') || (end[0] == 'm' && end[1] == 'B'))
            return false;
        scale = end[0] == 'K' || end[0] == 'k' ? 1ULL << 10 : 1ULL << 20;
    }
    return whole_number(text, end, (1ULL << 62) / scale, &value);
}

// OpenCV's boolean: 1, True, true, TRUE, 0, False, false, FALSE (nothing else).
bool good_boolean(const char *text)
{
    static const char *const kWords[] = {"1", "True", "true", "TRUE", "0", "False", "false", "FALSE"};
    for (const char *word : kWords)
        if (std::strcmp(text, word) == 0) return true;
    return false;
}

bool is_off(const char *text)
{
    return std::strcmp(text, "0") == 0 || std::strcmp(text, "False") == 0 || std::strcmp(text, "false") == 0 ||
           std::strcmp(text, "FALSE") == 0;
}

// "" when `given` is good for v, else what it must be.
const char *rule_broken(const Variable &v, const char *given)
{
    unsigned long long pixels;
    switch (v.kind) {
    case Kind::kPixels:
        return whole_number(given, given + std::strlen(given), static_cast<unsigned long long>(kMaxFramePixels), &pixels) &&
                       pixels >= 1
                   ? ""
                   : "is not a whole number of pixels from 1 to 33177600";  // kMaxFramePixels: asserted below
    case Kind::kSize: return good_size(given) ? "" : "is not a size OpenCV reads (digits, then nothing, KB or MB)";
    case Kind::kBoolean: return good_boolean(given) ? "" : "is not a boolean OpenCV reads (1, 0, true, false, True, ...)";
    case Kind::kOff:
        return is_off(given) ? ""
                             : "would have OpenCV write OpenCVTrace.txt into the current folder, unchecked: "
                               "hkf does not take it (unset it, or set it to 0)";
    }
    return "";
}

// The environment as the loader gives it: setenv here would not last (the C library's own initializer,
// which runs later, takes this array as the environment again), so a bad entry is changed in place: the
// pixel cap replaced by ours, any other taken out (the entries after it moved up).
void settle_opencv_environment(int, char **, char **environment)
{
    static char ours[64];
    std::snprintf(ours, sizeof ours, "OPENCV_IO_MAX_IMAGE_PIXELS=%lld", static_cast<long long>(kMaxFramePixels));
    for (char **entry = environment; entry != nullptr && *entry != nullptr;) {
        const char *broken = "";
        const Variable *which = nullptr;
        for (const Variable &v : kVariables) {
            const size_t length = std::strlen(v.name);
            if (std::strncmp(*entry, v.name, length) != 0 || (*entry)[length] != '=') continue;
            which = &v;
            broken = rule_broken(v, *entry + length + 1);
            break;
        }
        if (*broken == '\0') {
            ++entry;
            continue;
        }
        const char *given = *entry + std::strlen(which->name) + 1;
        if (problem[0] == '\0')
            std::snprintf(problem, sizeof problem, "%s='%.40s%s' %s", which->name, given,
                          std::strlen(given) > 40 ? "..." : "", broken);
        if (which->kind == Kind::kPixels) {
            *entry++ = ours;  // OpenCV loads with hkf's cap
            continue;
        }
        for (char **later = entry; *later != nullptr; ++later) later[0] = later[1];  // taken out
    }
}

}  // namespace

// Run by the loader before the libraries' initializers (only an executable's .preinit_array is run).
__attribute__((section(".preinit_array"), used)) void (*const settle_opencv_environment_first)(int, char **, char **) =
    settle_opencv_environment;

const char *opencv_environment_problem() { return problem; }

}  // namespace hkf_estimator
