// onnx_check.hpp - a model file checked before OpenCV's ONNX importer reads it. The importer trusts each
// tensor's declared shape: a weight whose data is shorter than its shape is read past its end (a
// heap-buffer-overflow in cv::Mat::copyTo, angles 100-245 deg off), and a huge declared shape crashes the
// process while it loads. This walks the file's protobuf itself (the wire format and the fields of
// onnx.proto that hold tensors; no ONNX library) and refuses a file where any tensor - an initializer, a
// node attribute's tensor, in the graph or in any subgraph or function - has a data length other than its
// shape and type give, a negative or out-of-bound dimension, external or segmented data, or a type it does
// not know; or where the bytes are no protobuf at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace hkf_estimator {

// "" when every tensor of the ONNX model in the bytes holds exactly the data its shape and type declare;
// else why not, naming the tensor.
std::string onnx_model_problem(const std::uint8_t *data, std::size_t size);

}  // namespace hkf_estimator
