// test_fast_layers.cpp - the layers the estimator gives OpenCV's DNN module
// (estimator/src/models/layers/, registered by fast_layers.cpp), run inside cv::dnn::Net as a rewritten graph runs
// them, against plain loops in double written here: the depthwise convolution at WHENet's
// kernel sizes, strides and asymmetric paddings, on planes from 7 x 7 to 112 x 112, with its
// planes' means; the pointwise convolution on planes that end in part of a tile or in columns, with output
// channels that end in part of one, gated (the weights scaled, the input, or each pixel tile's input), with a
// residual added, without a bias; the k x k convolution unfolded onto it, at WHENet's first layer's shape and at odd
// strides and paddings; a squeeze-and-excitation's gate from its means;
// the swish alone, fused by OpenCV into a convolution before it, and over its whole range; bad
// attributes and weights refused when the layer is made. All of it once per instruction-set level this
// CPU runs (simd_level.hpp), each level's layers against the same loops; and HKF_SIMD's values read.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmath>
#include <random>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include "fast_layers.hpp"
#include "model_spec.hpp"
#include "simd_level.hpp"

extern "C" {  // last: cmocka's fail() macro would break the C++ headers
#include <cmocka.h>
}

namespace {

struct Case {
    int channels, height, width, kernel, stride, top, left, bottom, right, swish;
};

double swish_reference(double x) { return x / (1.0 + std::exp(-x)); }

cv::Mat random_blob(std::vector<int> shape, unsigned seed, float spread)
{
    std::mt19937 random(seed);
    std::normal_distribution<float> normal(0.0f, spread);
    cv::Mat m(static_cast<int>(shape.size()), shape.data(), CV_32F);
    for (size_t i = 0; i < m.total(); ++i) m.ptr<float>()[i] = normal(random);
    return m;
}

cv::dnn::LayerParams swish_params()
{
    cv::dnn::LayerParams p;
    p.name = "swish";
    p.type = "hkf.Swish";
    return p;
}

cv::dnn::LayerParams depthwise_params(const Case &c, const cv::Mat &weights, const cv::Mat &bias)
{
    cv::dnn::LayerParams p;
    p.name = "dw";
    p.type = "hkf.DepthwiseConv";
    p.set("kernel", c.kernel);
    p.set("stride", c.stride);
    p.set("pad_top", c.top);
    p.set("pad_left", c.left);
    p.set("pad_bottom", c.bottom);
    p.set("pad_right", c.right);
    p.set("swish", c.swish);
    p.blobs = {weights, bias};
    return p;
}

// The largest |layer - reference| over the output, relative to the output's largest magnitude.
double depthwise_error(const Case &c, int images = 1)
{
    const cv::Mat input = random_blob({images, c.channels, c.height, c.width}, 1, 1.0f);
    const cv::Mat weights = random_blob({c.channels, 1, c.kernel, c.kernel}, 2, 0.3f);
    const cv::Mat bias = random_blob({c.channels}, 3, 0.5f);
    cv::dnn::Net net;
    cv::dnn::LayerParams params = depthwise_params(c, weights, bias);
    net.addLayerToPrev(params.name, params.type, params);
    net.setInput(input);
    const cv::Mat out = net.forward();
    const int out_h = (c.height + c.top + c.bottom - c.kernel) / c.stride + 1;
    const int out_w = (c.width + c.left + c.right - c.kernel) / c.stride + 1;
    assert_int_equal(out.dims, 4);
    assert_int_equal(out.size[0], images);
    assert_int_equal(out.size[1], c.channels);
    assert_int_equal(out.size[2], out_h);
    assert_int_equal(out.size[3], out_w);
    double worst = 0.0, scale = 1e-6;
    for (int p = 0; p < images * c.channels; ++p) {
        const int ch = p % c.channels;
        for (int oy = 0; oy < out_h; ++oy) {
            for (int ox = 0; ox < out_w; ++ox) {
                double sum = bias.ptr<float>()[ch];
                for (int ky = 0; ky < c.kernel; ++ky) {
                    for (int kx = 0; kx < c.kernel; ++kx) {
                        const int y = oy * c.stride + ky - c.top, x = ox * c.stride + kx - c.left;
                        if (y < 0 || y >= c.height || x < 0 || x >= c.width) continue;  // the zero padding
                        sum += static_cast<double>(weights.ptr<float>()[(ch * c.kernel + ky) * c.kernel + kx]) *
                               input.ptr<float>()[(p * c.height + y) * c.width + x];
                    }
                }
                const double expected = c.swish ? swish_reference(sum) : sum;
                const double got = out.ptr<float>()[(p * out_h + oy) * out_w + ox];
                worst = std::max(worst, std::fabs(got - expected));
                scale = std::max(scale, std::fabs(expected));
            }
        }
    }
    return worst / scale;
}

void test_depthwise_matches_the_loops(void **)
{
    const Case cases[] = {
        {8, 112, 112, 3, 1, 1, 1, 1, 1, 1},   // WHENet's first stage
        {6, 112, 112, 3, 2, 0, 0, 1, 1, 1},   // TF's "same" at stride 2: the padding after
        {5, 56, 56, 5, 2, 1, 1, 2, 2, 1},
        {7, 14, 14, 5, 1, 2, 2, 2, 2, 1},
        {9, 7, 7, 5, 1, 2, 2, 2, 2, 0},       // planes narrower than a vector
        {4, 13, 10, 3, 2, 1, 0, 1, 2, 0},     // odd sizes, every side padded differently
        {3, 9, 11, 7, 3, 3, 0, 2, 1, 1},      // a kernel and stride without a template of their own
        {3, 1, 1, 3, 1, 1, 1, 1, 1, 1},       // round 6's review: a 1 x 1 image (every tap but the centre padding)
        {5, 1, 7, 3, 2, 1, 1, 1, 1, 0},       // one row
        {2, 1024, 1536, 3, 2, 1, 1, 1, 1, 1}, // a large image
        {3, 37, 70, 3, 1, 1, 1, 1, 1, 1},     // wide rows interleaved row by row, each ending part way through a block
        {3, 73, 90, 5, 2, 2, 2, 2, 2, 0},     // the same at stride 2
        {2, 120, 100, 5, 1, 2, 2, 2, 2, 1},   // planes over 56 x 56 go plane by plane: 5 x 5 there
        {3, 150, 130, 5, 2, 2, 2, 2, 2, 0},
        // small planes interleaved whole, their last pixels (fewer than a block) over more than a row: 5 x 6 at
        // AVX-512 (14 of 30), 3 x 5 at AVX2 (7 of 15), 7 x 1 at SSE2 and NEON (3 of 7)
        {3, 5, 6, 3, 1, 1, 1, 1, 1, 1},
        {3, 3, 5, 3, 1, 1, 1, 1, 1, 0},
        {3, 7, 1, 3, 1, 1, 1, 1, 1, 1},
        // inputs of 56 x 56 and more interleaved 8 channels at a time at AVX-512: 19 channels end a block part way
        {19, 56, 56, 3, 1, 1, 1, 1, 1, 1},
        {19, 112, 112, 3, 2, 0, 0, 1, 1, 1},
    };
    for (const Case &c : cases) {
        const double error = depthwise_error(c);
        print_message("depthwise %dx%d, k %d, stride %d, pads %d %d %d %d, swish %d: relative error %.2e\n", c.height,
                      c.width, c.kernel, c.stride, c.top, c.left, c.bottom, c.right, c.swish, error);
        assert_true(error < 1e-5);
    }
    // two images of small planes, a vector's channels at once, 19 channels (a block ends part way at every level)
    const double error = depthwise_error(Case{19, 7, 7, 5, 1, 2, 2, 2, 2, 1}, 2);
    print_message("depthwise 2 images of 19 x 7 x 7, k 5: relative error %.2e\n", error);
    assert_true(error < 1e-5);
}

void test_swish_over_its_range(void **)
{
    std::vector<float> x;
    for (int i = -20000; i <= 20000; ++i) x.push_back(static_cast<float>(i) * 0.01f);  // -200 .. 200
    x.push_back(-1e5f);
    x.push_back(1e5f);
    std::vector<float> y(x.size());
    hkf_estimator::swish_in_place(x.data(), y.data(), static_cast<long>(x.size()));
    double worst = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double expected = swish_reference(x[i]);
        worst = std::max(worst, std::fabs(y[i] - expected) / std::max(1.0, std::fabs(expected)));
    }
    print_message("swish on [-200, 200] and +-1e5: largest error %.2e (relative beyond 1)\n", worst);
    assert_true(worst < 5e-7);
    hkf_estimator::swish_in_place(x.data(), x.data(), static_cast<long>(x.size()));  // in place
    for (size_t i = 0; i < x.size(); ++i) assert_true(x[i] == y[i]);
}

// A 1x1 convolution then hkf.Swish: OpenCV fuses the swish into the convolution (forwardSlice on
// each stripe of its output); the result is the convolution's, then the swish.
void test_swish_fused_into_a_convolution(void **)
{
    const int in_c = 16, out_c = 24, size = 20;
    const cv::Mat input = random_blob({1, in_c, size, size}, 4, 1.0f);
    const cv::Mat weights = random_blob({out_c, in_c, 1, 1}, 5, 0.4f);
    const cv::Mat bias = random_blob({out_c}, 6, 0.5f);
    cv::dnn::LayerParams conv;
    conv.name = "conv";
    conv.type = "Convolution";
    conv.set("kernel_size", 1);
    conv.set("num_output", out_c);
    conv.set("bias_term", true);
    conv.blobs = {weights, bias};
    cv::dnn::Net plain;
    plain.addLayerToPrev(conv.name, conv.type, conv);
    plain.setInput(input);
    const cv::Mat linear = plain.forward().clone();
    cv::dnn::Net fused;
    fused.addLayerToPrev(conv.name, conv.type, conv);
    cv::dnn::LayerParams swish = swish_params();
    fused.addLayerToPrev(swish.name, swish.type, swish);
    fused.setInput(input);
    const cv::Mat out = fused.forward();
    std::vector<double> times;
    (void)fused.getPerfProfile(times);
    assert_int_equal(static_cast<int>(times.size()), 2);
    assert_true(times[1] == 0.0);  // the swish layer skipped: fused, run by the convolution
    assert_int_equal(static_cast<int>(out.total()), static_cast<int>(linear.total()));
    double worst = 0.0;
    for (size_t i = 0; i < out.total(); ++i)
        worst = std::max(worst, std::fabs(out.ptr<float>()[i] - swish_reference(linear.ptr<float>()[i])));
    print_message("1x1 convolution + swish: largest |error| %.2e\n", worst);
    assert_true(worst < 1e-5);
}

// hkf.Swish where nothing can take it in (the network's first layer): its own forward.
void test_swish_as_a_layer(void **)
{
    const cv::Mat input = random_blob({1, 3, 9, 9}, 9, 3.0f);
    cv::dnn::Net net;
    cv::dnn::LayerParams swish = swish_params();
    net.addLayerToPrev(swish.name, swish.type, swish);
    net.setInput(input);
    const cv::Mat out = net.forward();
    assert_int_equal(static_cast<int>(out.total()), static_cast<int>(input.total()));
    for (size_t i = 0; i < out.total(); ++i)
        assert_true(std::fabs(out.ptr<float>()[i] - swish_reference(input.ptr<float>()[i])) < 1e-5);
}

// The depthwise layer's second output (means = 1): each output plane's mean, plane by plane (60 x 60) and a
// vector's channels at once (14 x 14; 7 x 7 in two images of 11 channels, so that a block ends part way; 56 x 56 at
// stride 2, 8 channels a block at AVX-512).
void check_depthwise_means(const Case &c, int images)
{
    const cv::Mat input = random_blob({images, c.channels, c.height, c.width}, 10, 1.0f);
    cv::dnn::LayerParams params =
        depthwise_params(c, random_blob({c.channels, 1, c.kernel, c.kernel}, 11, 0.3f), random_blob({c.channels}, 12, 0.5f));
    params.set("means", 1);
    cv::dnn::Net net;
    net.addLayerToPrev(params.name, params.type, params);
    net.setInput(input);
    std::vector<std::vector<cv::Mat>> outputs;  // every output of the layer "dw"
    net.forward(outputs, std::vector<cv::String>{"dw"});
    assert_int_equal(static_cast<int>(outputs[0].size()), 2);
    const cv::Mat &planes = outputs[0][0], &means = outputs[0][1];
    assert_int_equal(static_cast<int>(means.total()), images * c.channels);
    const int plane = planes.size[2] * planes.size[3];
    for (int p = 0; p < images * c.channels; ++p) {
        double sum = 0.0;
        for (int i = 0; i < plane; ++i) sum += planes.ptr<float>()[p * plane + i];
        assert_true(std::fabs(means.ptr<float>()[p] - sum / plane) < 1e-5);
    }
}

void test_depthwise_means(void **)
{
    check_depthwise_means(Case{3, 60, 60, 3, 1, 1, 1, 1, 1, 1}, 1);
    check_depthwise_means(Case{6, 14, 14, 5, 1, 2, 2, 2, 2, 1}, 1);
    check_depthwise_means(Case{11, 7, 7, 3, 1, 1, 1, 1, 1, 1}, 2);
    check_depthwise_means(Case{10, 56, 56, 5, 2, 1, 1, 2, 2, 1}, 2);  // 8 channels a block at AVX-512 (56 x 56 and more)
}

struct PointwiseCase {
    int in_c, out_c, height, width, swish, bias, gate, residual;
};

// The largest |layer - reference| of a 1x1 convolution, relative to the output's largest magnitude.
double pointwise_error(const PointwiseCase &c)
{
    const cv::Mat input = random_blob({1, c.in_c, c.height, c.width}, 13, 1.0f);
    const cv::Mat weights = random_blob({c.out_c, c.in_c, 1, 1}, 14, 0.3f);
    const cv::Mat bias = random_blob({c.out_c}, 15, 0.5f);
    cv::Mat gate = random_blob({1, c.in_c, 1, 1}, 16, 1.0f);
    const cv::Mat skip = random_blob({1, c.out_c, c.height, c.width}, 17, 1.0f);
    for (size_t i = 0; i < gate.total(); ++i) gate.ptr<float>()[i] = 1.0f / (1.0f + std::exp(-gate.ptr<float>()[i]));
    cv::dnn::LayerParams p;
    p.name = "pw";
    p.type = "hkf.PointwiseConv";
    p.set("swish", c.swish);
    p.set("residual", c.residual);
    p.blobs = {weights};
    if (c.bias) p.blobs.push_back(bias);
    cv::dnn::Net net;
    const int id = net.addLayer(p.name, p.type, p);
    std::vector<cv::String> names = {"x"};  // the layer's inputs: x, the gate, the residual
    if (c.gate) names.push_back("g");
    if (c.residual) names.push_back("r");
    net.setInputsNames(names);
    for (int k = 0; k < static_cast<int>(names.size()); ++k) net.connect(0, k, id, k);
    net.setInput(input, "x");
    if (c.gate) net.setInput(gate, "g");
    if (c.residual) net.setInput(skip, "r");
    const cv::Mat out = net.forward("pw");
    const int pixels = c.height * c.width;
    assert_int_equal(static_cast<int>(out.total()), c.out_c * pixels);
    double worst = 0.0, scale = 1e-6;
    for (int o = 0; o < c.out_c; ++o) {
        for (int i = 0; i < pixels; ++i) {
            double sum = c.bias ? bias.ptr<float>()[o] : 0.0;
            for (int k = 0; k < c.in_c; ++k)
                sum += static_cast<double>(weights.ptr<float>()[o * c.in_c + k]) * input.ptr<float>()[k * pixels + i] *
                       (c.gate ? gate.ptr<float>()[k] : 1.0f);
            const double expected = (c.swish ? swish_reference(sum) : sum) + (c.residual ? skip.ptr<float>()[o * pixels + i] : 0.0);
            worst = std::max(worst, std::fabs(out.ptr<float>()[o * pixels + i] - expected));
            scale = std::max(scale, std::fabs(expected));
        }
    }
    return worst / scale;
}

void test_pointwise_matches_the_loops(void **)
{
    const PointwiseCase cases[] = {
        {16, 96, 112, 112, 1, 1, 0, 0},  // WHENet's first expansion: whole tiles
        {32, 16, 56, 56, 0, 1, 1, 0},    // gated, more pixels than outputs: the weights scaled
        {240, 80, 14, 14, 1, 1, 0, 0},   // 196 pixels: six tiles and 4 pixels
        {1152, 320, 7, 7, 0, 1, 1, 0},   // gated, fewer pixels than outputs: the input scaled
        {672, 112, 14, 14, 1, 1, 1, 0},  // gated, many inputs, more pixels than outputs: each pixel tile's input scaled
        {200, 40, 7, 7, 0, 1, 1, 0},     // the same, the last tile ending in a column
        {20, 21, 5, 4, 1, 0, 0, 0},      // no bias; 21 outputs end in part of a tile, 20 pixels in part of one
        {9, 3, 33, 1, 0, 0, 1, 0},
        {64, 13, 37, 37, 1, 1, 0, 0},    // few inputs: blocks of pixel tiles, the last block ending in part of a tile
        {64, 6, 41, 41, 0, 1, 0, 0},     // the last block ending in one pixel: a column
        {24, 10, 5, 13, 1, 1, 0, 0},     // 65 pixels: a narrow tile and a column after a tile (AVX-512's 48 pixels)
        {200, 40, 5, 13, 0, 1, 1, 0},    // the same, gated in the pixel tiles
        {40, 21, 5, 10, 1, 0, 0, 0},     // 50 pixels: two columns after the tiles; outputs ending in part of a tile
        {12, 7, 1, 2, 1, 1, 1, 0},       // two pixels in all: columns alone
        {30, 16, 1, 1, 0, 1, 0, 0},      // one
        {672, 112, 14, 14, 0, 1, 1, 1},  // gated in the pixel tiles, a residual added (a projection of WHENet's)
        {40, 21, 5, 10, 1, 0, 1, 1},     // a residual after the swish, on tiles, columns and outputs that end in part of one
        {24, 40, 56, 56, 0, 1, 0, 1},    // on blocks of pixel tiles
    };
    for (const PointwiseCase &c : cases) {
        const double error = pointwise_error(c);
        print_message("pointwise %d -> %d on %dx%d, swish %d, bias %d, gate %d, residual %d: relative error %.2e\n",
                      c.in_c, c.out_c, c.height, c.width, c.swish, c.bias, c.gate, c.residual, error);
        assert_true(error < 1e-5);
    }
}

// hkf.UnfoldedConv: a k x k convolution of every input channel (Case's channels: the input's; out_c
// outputs) against the loops, relative to the output's largest magnitude; after an image of another shape.
double unfolded_error(const Case &c, int out_c)
{
    const cv::Mat input = random_blob({1, c.channels, c.height, c.width}, 18, 1.0f);
    const cv::Mat weights = random_blob({out_c, c.channels, c.kernel, c.kernel}, 19, 0.3f);
    const cv::Mat bias = random_blob({out_c}, 20, 0.5f);
    cv::dnn::LayerParams p = depthwise_params(c, weights, bias);
    p.name = "unfolded";
    p.type = "hkf.UnfoldedConv";
    cv::dnn::Net net;
    net.addLayerToPrev(p.name, p.type, p);
    // A larger image first: the layer's unfolded rows, zeroed once for a shape, must be zeroed anew for this one.
    net.setInput(random_blob({1, c.channels, c.height + 4, c.width + 3}, 21, 1.0f));
    net.forward();
    net.setInput(input);
    const cv::Mat out = net.forward();
    const int out_h = (c.height + c.top + c.bottom - c.kernel) / c.stride + 1;
    const int out_w = (c.width + c.left + c.right - c.kernel) / c.stride + 1;
    assert_int_equal(out.size[1], out_c);
    assert_int_equal(out.size[2], out_h);
    assert_int_equal(out.size[3], out_w);
    double worst = 0.0, scale = 1e-6;
    for (int o = 0; o < out_c; ++o)
        for (int oy = 0; oy < out_h; ++oy)
            for (int ox = 0; ox < out_w; ++ox) {
                double sum = bias.ptr<float>()[o];
                for (int ch = 0; ch < c.channels; ++ch)
                    for (int ky = 0; ky < c.kernel; ++ky)
                        for (int kx = 0; kx < c.kernel; ++kx) {
                            const int y = oy * c.stride + ky - c.top, x = ox * c.stride + kx - c.left;
                            if (y < 0 || y >= c.height || x < 0 || x >= c.width) continue;  // the zero padding
                            sum += static_cast<double>(weights.ptr<float>()[((o * c.channels + ch) * c.kernel + ky) * c.kernel + kx]) *
                                   input.ptr<float>()[(ch * c.height + y) * c.width + x];
                        }
                const double expected = c.swish ? swish_reference(sum) : sum;
                worst = std::max(worst, std::fabs(out.ptr<float>()[(o * out_h + oy) * out_w + ox] - expected));
                scale = std::max(scale, std::fabs(expected));
            }
    return worst / scale;
}

void test_unfolded_matches_the_loops(void **)
{
    const struct {
        Case c;
        int out_c;
    } cases[] = {
        {{3, 224, 224, 3, 2, 0, 0, 1, 1, 1}, 32},  // WHENet's first convolution, TF's "same" at stride 2
        {{5, 9, 11, 3, 1, 1, 1, 1, 1, 0}, 7},      // stride 1; outputs that end in part of a tile
        {{2, 13, 10, 5, 3, 2, 0, 1, 4, 1}, 9},     // a stride of 3, every side padded differently
        {{4, 1, 1, 3, 1, 1, 1, 1, 1, 0}, 6},       // a 1 x 1 image: every tap but the centre padding
    };
    for (const auto &u : cases) {
        const double error = unfolded_error(u.c, u.out_c);
        print_message("unfolded %d -> %d on %dx%d, k %d, stride %d, pads %d %d %d %d, swish %d: relative error %.2e\n",
                      u.c.channels, u.out_c, u.c.height, u.c.width, u.c.kernel, u.c.stride, u.c.top, u.c.left, u.c.bottom,
                      u.c.right, u.c.swish, error);
        assert_true(error < 1e-5);
    }
}

// hkf.SqueezeExcite: the gate sigmoid(W2 swish(W1 m + b1) + b2) of two images' means, against the loops.
// The largest |gate - reference| of a squeeze-and-excitation of two images (each its own gate).
double squeeze_excite_error(int channels, int reduced)
{
    const int images = 2;
    const cv::Mat means = random_blob({images, channels, 1, 1}, 23, 1.0f);
    cv::dnn::LayerParams p;
    p.name = "se";
    p.type = "hkf.SqueezeExcite";
    p.blobs = {random_blob({reduced, channels, 1, 1}, 24, 0.1f), random_blob({reduced}, 25, 0.5f),
               random_blob({channels, reduced, 1, 1}, 26, 0.3f), random_blob({channels}, 27, 0.5f)};
    cv::dnn::Net net;
    net.addLayerToPrev(p.name, p.type, p);
    net.setInput(means);
    const cv::Mat gate = net.forward();
    assert_int_equal(static_cast<int>(gate.total()), images * channels);
    double worst = 0.0;
    for (int image = 0; image < images; ++image) {
        std::vector<double> hidden(reduced);
        for (int r = 0; r < reduced; ++r) {
            double sum = p.blobs[1].ptr<float>()[r];
            for (int c = 0; c < channels; ++c)
                sum += static_cast<double>(p.blobs[0].ptr<float>()[r * channels + c]) * means.ptr<float>()[image * channels + c];
            hidden[r] = swish_reference(sum);
        }
        for (int c = 0; c < channels; ++c) {
            double sum = p.blobs[3].ptr<float>()[c];
            for (int r = 0; r < reduced; ++r) sum += static_cast<double>(p.blobs[2].ptr<float>()[c * reduced + r]) * hidden[r];
            worst = std::max(worst, std::fabs(gate.ptr<float>()[image * channels + c] - 1.0 / (1.0 + std::exp(-sum))));
        }
    }
    print_message("squeeze-and-excitation %d -> %d -> %d, 2 images: largest |error| %.2e\n", channels, reduced, channels, worst);
    return worst;
}

void test_squeeze_excite_matches_the_loops(void **)
{
    assert_true(squeeze_excite_error(1152, 48) < 1e-5);  // WHENet's widest: on two threads
    assert_true(squeeze_excite_error(96, 4) < 1e-5);     // its narrowest: on one
}

// The layer refused when it is made (its constructor throws).
bool creation_refused(cv::dnn::LayerParams p)
{
    try {
        (void)cv::dnn::LayerFactory::createLayerInstance(p.type, p);
    } catch (const cv::Exception &) {
        return true;
    }
    return false;
}

bool refused(Case c, int weight_kernel, int bias_size)
{
    const cv::Mat weights = random_blob({c.channels, 1, weight_kernel, weight_kernel}, 7, 1.0f);
    const cv::Mat bias = random_blob({bias_size}, 8, 1.0f);
    return creation_refused(depthwise_params(c, weights, bias));
}

// A 3 -> 5 pointwise convolution on 4 x 4 with a residual of skip_channels channels refused when the net is run.
bool residual_refused(int skip_channels)
{
    cv::dnn::LayerParams p;
    p.name = "pw";
    p.type = "hkf.PointwiseConv";
    p.set("residual", 1);
    p.blobs = {random_blob({5, 3, 1, 1}, 33, 1.0f)};
    cv::dnn::Net net;
    const int id = net.addLayer(p.name, p.type, p);
    net.setInputsNames({"x", "r"});
    net.connect(0, 0, id, 0);
    net.connect(0, 1, id, 1);
    net.setInput(random_blob({1, 3, 4, 4}, 34, 1.0f), "x");
    net.setInput(random_blob({1, skip_channels, 4, 4}, 35, 1.0f), "r");
    try {
        net.forward("pw");
    } catch (const cv::Exception &) {
        return true;
    }
    return false;
}

void test_bad_layers_refused(void **)
{
    const Case good = {4, 8, 8, 3, 1, 1, 1, 1, 1, 1};
    assert_false(refused(good, 3, 4));
    Case c = good;
    c.kernel = 0;
    assert_true(refused(c, 3, 4));  // no kernel
    c = good;
    c.stride = 0;
    assert_true(refused(c, 3, 4));
    c = good;
    c.bottom = 3;
    assert_true(refused(c, 3, 4));  // a padding as wide as the kernel: outputs of padding alone
    c = good;
    c.left = -1;
    assert_true(refused(c, 3, 4));
    assert_true(refused(good, 5, 4));  // weights of another kernel size
    assert_true(refused(good, 3, 3));  // a bias per channel missing
    cv::dnn::LayerParams p;
    p.type = "hkf.PointwiseConv";
    p.blobs = {random_blob({4, 3, 3, 3}, 17, 1.0f)};  // not 1x1
    assert_true(creation_refused(p));
    assert_false(residual_refused(5));  // good: taken
    assert_true(residual_refused(4));   // a residual of another shape than the output
    p = depthwise_params(good, random_blob({4, 3, 3, 3}, 21, 1.0f), random_blob({4}, 22, 1.0f));
    p.type = "hkf.UnfoldedConv";
    assert_false(creation_refused(p));  // good: taken
    p.set("pad_left", 3);  // a padding as wide as the kernel
    assert_true(creation_refused(p));
    cv::dnn::LayerParams se;
    se.type = "hkf.SqueezeExcite";
    se.blobs = {random_blob({4, 8, 1, 1}, 28, 1.0f), random_blob({4}, 29, 1.0f), random_blob({8, 4, 1, 1}, 30, 1.0f),
                random_blob({8}, 31, 1.0f)};
    assert_false(creation_refused(se));  // good: taken
    se.blobs[2] = random_blob({8, 5, 1, 1}, 32, 1.0f);  // W2 reads 5 values where W1 makes 4
    assert_true(creation_refused(se));
    se.blobs.pop_back();  // no b2
    assert_true(creation_refused(se));
}

// The levels this CPU runs, best first, down to the baseline, which can always be chosen.
void test_simd_levels_ordered(void **)
{
    using hkf_estimator::SimdLevel;
    const std::vector<SimdLevel> levels = hkf_estimator::simd_levels_supported();
    assert_true(!levels.empty());
    assert_true(levels.back() == SimdLevel::baseline);  // every CPU runs the baseline
    for (size_t i = 1; i < levels.size(); ++i) assert_true(levels[i - 1] > levels[i]);  // best first
    bool refused = false;
    try {
        hkf_estimator::use_simd_level(SimdLevel::baseline);
    } catch (const hkf_estimator::EstimatorError &) {
        refused = true;
    }
    assert_false(refused);
    assert_string_equal(hkf_estimator::layer_kernels_in_use().name, hkf_estimator::layer_kernels_of(SimdLevel::baseline).name);
}

}  // namespace

int main()
{
    hkf_estimator::register_fast_layers();
    hkf_estimator::register_fast_layers();  // twice: a second call changes nothing
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_depthwise_matches_the_loops),
        cmocka_unit_test(test_depthwise_means),
        cmocka_unit_test(test_pointwise_matches_the_loops),
        cmocka_unit_test(test_unfolded_matches_the_loops),
        cmocka_unit_test(test_squeeze_excite_matches_the_loops),
        cmocka_unit_test(test_swish_over_its_range),
        cmocka_unit_test(test_swish_fused_into_a_convolution),
        cmocka_unit_test(test_swish_as_a_layer),
        cmocka_unit_test(test_bad_layers_refused),
    };
    int failed = 0;
    for (hkf_estimator::SimdLevel level : hkf_estimator::simd_levels_supported()) {
        hkf_estimator::use_simd_level(level);  // the layers made from now on
        const char *name = hkf_estimator::layer_kernels_in_use().name;
        print_message("== the layers at %s\n", name);
        failed += _cmocka_run_group_tests(name, tests, sizeof tests / sizeof tests[0], nullptr, nullptr);
    }
    const struct CMUnitTest levels[] = {cmocka_unit_test(test_simd_levels_ordered)};
    return failed + cmocka_run_group_tests(levels, nullptr, nullptr);
}
