// fast_layers.cpp - see fast_layers.hpp: the layers' registration (each layer in layers/).
#include "fast_layers.hpp"

#include <mutex>

#include <opencv2/dnn.hpp>

#include "layers/layer_support.hpp"
#include "simd_level.hpp"

namespace hkf_estimator {

float plane_mean(const float *plane, long n) { return layer_kernels_in_use().plane_mean(plane, n); }

void swish_in_place(const float *src, float *dst, long n) { layer_kernels_in_use().swish(src, dst, n); }

void register_fast_layers()
{
    static std::once_flag once;
    std::call_once(once, [] {
        cv::dnn::LayerFactory::registerLayer("hkf.Swish", make_swish_layer);
        cv::dnn::LayerFactory::registerLayer("hkf.DepthwiseConv", make_depthwise_conv_layer);
        cv::dnn::LayerFactory::registerLayer("hkf.PointwiseConv", make_pointwise_conv_layer);
        cv::dnn::LayerFactory::registerLayer("hkf.UnfoldedConv", make_pointwise_conv_layer);
        cv::dnn::LayerFactory::registerLayer("hkf.SqueezeExcite", make_squeeze_excite_layer);
    });
}

}  // namespace hkf_estimator
