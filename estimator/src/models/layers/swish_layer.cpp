// swish_layer.cpp - "hkf.Swish", the swish as an activation (see fast_layers.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/shape_utils.hpp>

#include "layer_support.hpp"
#include "simd_level.hpp"

namespace hkf_estimator {

namespace {

// "hkf.Swish": an activation, so that OpenCV fuses it into the convolution before it (forwardSlice
// is then called on each stripe of that convolution's output).
class SwishLayer : public cv::dnn::ActivationLayer {
public:
    explicit SwishLayer(const cv::dnn::LayerParams &params) : kernels_(layer_kernels_in_use())
    {
        setParamsFrom(params);
    }


    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int required_outputs,
                         std::vector<cv::dnn::MatShape> &outputs,
                         std::vector<cv::dnn::MatShape> &internals) const override
    {
        Layer::getMemoryShapes(inputs, required_outputs, outputs, internals);
        return true;  // in place
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        Tensors t(inputs_arr, outputs_arr);
        for (size_t i = 0; i < t.in.size(); ++i)
            kernels_.swish(t.in[i].ptr<float>(), t.out[i].ptr<float>(), static_cast<long>(t.in[i].total()));
    }

    void forwardSlice(const float *src, float *dst, int len, size_t plane_size, int cn0, int cn1) const override
    {
        for (int c = cn0; c < cn1; ++c, src += plane_size, dst += plane_size) kernels_.swish(src, dst, len);
    }

private:
    const LayerKernels &kernels_;  // the level in use when the layer was made
};

}  // namespace

cv::Ptr<cv::dnn::Layer> make_swish_layer(cv::dnn::LayerParams &params) { return cv::makePtr<SwishLayer>(params); }

}  // namespace hkf_estimator
