// image_size_cap.cpp - see image_size_cap.hpp.
#include "image_size_cap.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "frame_source.hpp"  // kMaxFramePixels

namespace hkf_estimator {

namespace {

char problem[200];  // written once, before main and before any thread

const char kVariable[] = "OPENCV_IO_MAX_IMAGE_PIXELS";

// A whole number (digits only, no sign, no exponent) from 1 to kMaxFramePixels.
bool good_cap(const char *text)
{
    if (*text == '\0') return false;
    long long value = 0;
    for (const char *c = text; *c != '\0'; ++c) {
        if (*c < '0' || *c > '9') return false;
        value = value * 10 + (*c - '0');
        if (value > kMaxFramePixels) return false;  // checked at each digit: no overflow
    }
    return value >= 1;
}

// The environment as the loader gives it: setenv here would not last (the C library's own initializer,
// which runs later, takes this array as the environment again), so a bad entry is replaced in place.
void settle_image_size_cap(int, char **, char **environment)
{
    static char ours[64];
    const size_t name_length = sizeof kVariable - 1;
    std::snprintf(ours, sizeof ours, "%s=%lld", kVariable, static_cast<long long>(kMaxFramePixels));
    for (char **entry = environment; entry != nullptr && *entry != nullptr; ++entry) {
        if (std::strncmp(*entry, kVariable, name_length) != 0 || (*entry)[name_length] != '=') continue;
        const char *given = *entry + name_length + 1;
        if (good_cap(given)) continue;
        std::snprintf(problem, sizeof problem, "%s='%.40s%s' is not a whole number of pixels from 1 to %lld", kVariable,
                      given, std::strlen(given) > 40 ? "..." : "", static_cast<long long>(kMaxFramePixels));
        *entry = ours;  // OpenCV loads with hkf's cap; main reports the problem
    }
}

}  // namespace

// Run by the loader before the libraries' initializers (only an executable's .preinit_array is run).
__attribute__((section(".preinit_array"), used)) void (*const settle_image_size_cap_first)(int, char **, char **) =
    settle_image_size_cap;

const char *image_size_cap_problem() { return problem; }

}  // namespace hkf_estimator
