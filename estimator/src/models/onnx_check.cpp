// onnx_check.cpp - see onnx_check.hpp. The field numbers are onnx.proto's (ONNX IR version 8).
#include "onnx_check.hpp"

#include <cstdint>
#include <cstring>

namespace hkf_estimator {

namespace {

constexpr int kMaxDepth = 16;                  // graphs inside attributes inside graphs ...
constexpr int kMaxDims = 16;                   // a tensor's rank
constexpr std::uint64_t kMaxDim = 1ULL << 31;  // one dimension
constexpr std::uint64_t kMaxElements = 1ULL << 34;
// An integer tensor's values are sizes, axes, shapes and indices to OpenCV's importer, which allocates by
// them (a Slice's axis of 10^17 asked for 8 GB): each must be within +-2^24, or one of the extremes
// exporters write for "to the end" (INT32_MIN/MAX, INT64_MIN/MAX).
constexpr std::int64_t kMaxIntegerValue = 1LL << 24;

bool integer_value_ok(std::int64_t v)
{
    return (v >= -kMaxIntegerValue && v <= kMaxIntegerValue) || v == INT64_MAX || v == INT64_MIN ||
           v == INT32_MAX || v == INT32_MIN || v == INT64_MAX - 1 || v == INT64_MIN + 1;
}

enum Wire { kVarint = 0, kFixed64 = 1, kBytes = 2, kFixed32 = 5 };

// One field of a protobuf message: its number, wire type, and its value (a varint or fixed number) or bytes.
struct Field {
    std::uint32_t number = 0;
    int wire = 0;
    std::uint64_t value = 0;
    const std::uint8_t *bytes = nullptr;
    std::size_t length = 0;
};

// A message's bytes, read field by field; ok turns false on the first malformed byte.
struct Message {
    const std::uint8_t *at, *end;
    bool ok = true;

    Message(const std::uint8_t *data, std::size_t size) : at(data), end(data + size) {}

    bool varint(std::uint64_t &out)
    {
        out = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            if (at == end) return ok = false;
            const std::uint8_t byte = *at++;
            out |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
            if ((byte & 0x80) == 0) return true;
        }
        return ok = false;  // more than 10 bytes
    }

    // The next field, or false at the end (ok tells whether the end was clean).
    bool next(Field &f)
    {
        if (!ok || at == end) return false;
        std::uint64_t key;
        if (!varint(key) || (key >> 3) == 0 || (key >> 3) > 0x1fffffff) return ok = false;
        f.number = static_cast<std::uint32_t>(key >> 3);
        f.wire = static_cast<int>(key & 7);
        f.bytes = nullptr;
        f.length = 0;
        switch (f.wire) {
        case kVarint: return varint(f.value);
        case kFixed64:
        case kFixed32: {
            const std::size_t n = f.wire == kFixed64 ? 8 : 4;
            if (static_cast<std::size_t>(end - at) < n) return ok = false;
            f.bytes = at;
            f.length = n;
            at += n;
            return true;
        }
        case kBytes: {
            std::uint64_t n;
            if (!varint(n) || n > static_cast<std::uint64_t>(end - at)) return ok = false;
            f.bytes = at;
            f.length = static_cast<std::size_t>(n);
            at += n;
            return true;
        }
        default: return ok = false;  // groups (3, 4) and the undefined wire types
        }
    }
};

// TensorProto's element types: bytes per element in raw_data (0: none, a string), and which typed field
// holds the values otherwise, with how many values an element takes (complex numbers: 2).
struct ElementType {
    int raw_size;
    std::uint32_t typed_field;  // float_data 4, int32_data 5, string_data 6, int64_data 7, double_data 10, uint64_data 11
    int values_per_element;
};

bool element_type(std::uint64_t type, ElementType &out)
{
    switch (type) {
    case 1: out = {4, 4, 1}; return true;    // FLOAT
    case 2: out = {1, 5, 1}; return true;    // UINT8
    case 3: out = {1, 5, 1}; return true;    // INT8
    case 4: out = {2, 5, 1}; return true;    // UINT16
    case 5: out = {2, 5, 1}; return true;    // INT16
    case 6: out = {4, 5, 1}; return true;    // INT32
    case 7: out = {8, 7, 1}; return true;    // INT64
    case 8: out = {0, 6, 1}; return true;    // STRING
    case 9: out = {1, 5, 1}; return true;    // BOOL
    case 10: out = {2, 5, 1}; return true;   // FLOAT16
    case 11: out = {8, 10, 1}; return true;  // DOUBLE
    case 12: out = {4, 11, 1}; return true;  // UINT32
    case 13: out = {8, 11, 1}; return true;  // UINT64
    case 14: out = {8, 4, 2}; return true;   // COMPLEX64
    case 15: out = {16, 10, 2}; return true; // COMPLEX128
    case 16: out = {2, 5, 1}; return true;   // BFLOAT16
    default: return false;
    }
}

// The values in one occurrence of a repeated numeric field: packed (bytes) or one value.
bool count_values(const Field &f, std::uint64_t &count)
{
    const bool fixed32 = f.number == 4, fixed64 = f.number == 10;
    if (f.wire != kBytes) {  // unpacked: one value, of the field's own wire type
        if ((fixed32 && f.wire != kFixed32) || (fixed64 && f.wire != kFixed64) || (!fixed32 && !fixed64 && f.wire != kVarint))
            return false;
        ++count;
        return true;
    }
    if (fixed32 || fixed64) {
        const std::size_t size = fixed32 ? 4 : 8;
        if (f.length % size != 0) return false;
        count += f.length / size;
        return true;
    }
    Message packed(f.bytes, f.length);
    std::uint64_t ignored;
    while (packed.at != packed.end) {
        if (!packed.varint(ignored)) return false;
        ++count;
    }
    return true;
}

// The values of an int32_data or int64_data field (varints; a negative int32 is sign-extended to 64 bits).
bool typed_integers_ok(const Field &f)
{
    if (f.wire == kVarint) return integer_value_ok(static_cast<std::int64_t>(f.value));
    Message packed(f.bytes, f.length);
    std::uint64_t v;
    while (packed.at != packed.end)
        if (!packed.varint(v) || !integer_value_ok(static_cast<std::int64_t>(v))) return false;
    return true;
}

// The little-endian INT32 (size 4) or INT64 (size 8) values of raw data.
bool raw_integers_ok(const std::uint8_t *raw, std::size_t length, int size)
{
    for (std::size_t i = 0; raw != nullptr && i + static_cast<std::size_t>(size) <= length; i += static_cast<std::size_t>(size)) {
        std::int64_t v;
        if (size == 8) {
            std::uint64_t u = 0;
            for (int b = 7; b >= 0; --b) u = (u << 8) | raw[i + static_cast<std::size_t>(b)];
            std::memcpy(&v, &u, sizeof v);
        } else {
            std::uint32_t u = 0;
            for (int b = 3; b >= 0; --b) u = (u << 8) | raw[i + static_cast<std::size_t>(b)];
            std::int32_t w;
            std::memcpy(&w, &u, sizeof w);
            v = w;
        }
        if (!integer_value_ok(v)) return false;
    }
    return true;
}

std::string tensor_problem(const std::uint8_t *data, std::size_t size);
std::string graph_problem(const std::uint8_t *data, std::size_t size, int depth);

std::string tensor_problem(const std::uint8_t *data, std::size_t size)
{
    Message m(data, size);
    Field f;
    std::string name;
    std::uint64_t dims = 0, elements = 1, type = 0, typed_values = 0, typed_field_seen = 0, strings = 0;
    std::uint64_t values[12] = {};
    bool has_raw = false, external = false, values_ok = true;
    std::size_t raw_length = 0;
    const std::uint8_t *raw = nullptr;
    bool bad_dim = false;
    while (m.next(f)) {
        switch (f.number) {
        case 1: {  // dims: int64, packed or not
            auto dimension = [&](std::uint64_t d) {
                ++dims;
                if (static_cast<std::int64_t>(d) < 0 || d > kMaxDim) bad_dim = true;
                else if (!bad_dim && d != 0 && elements > kMaxElements / d) bad_dim = true;
                else elements *= d;
            };
            if (f.wire == kVarint) {
                dimension(f.value);
            } else if (f.wire == kBytes) {
                Message packed(f.bytes, f.length);
                std::uint64_t d;
                while (packed.at != packed.end) {
                    if (!packed.varint(d)) return "a dimension list that is no protobuf";
                    dimension(d);
                }
            } else {
                return "dimensions of the wrong wire type";
            }
            break;
        }
        case 2:
            if (f.wire != kVarint) return "a data type of the wrong wire type";
            type = f.value;
            break;
        case 8:
            if (f.wire == kBytes) name.assign(reinterpret_cast<const char *>(f.bytes), f.length < 80 ? f.length : 80);
            break;
        case 9:
            if (f.wire != kBytes) return "raw data of the wrong wire type";
            has_raw = true;
            raw = f.bytes;
            raw_length += f.length;
            break;
        case 6:  // string_data
            if (f.wire != kBytes) return "string data of the wrong wire type";
            ++strings;
            break;
        case 4: case 5: case 7: case 10: case 11:
            if (!count_values(f, values[f.number])) return "typed data that is no protobuf";
            if ((f.number == 5 || f.number == 7) && !typed_integers_ok(f)) values_ok = false;
            break;
        case 3: return "tensor '" + name + "' is split into segments (not taken)";
        case 13: external = true; break;
        case 14:
            if (f.wire == kVarint && f.value == 1) external = true;
            break;
        default: break;
        }
    }
    if (!m.ok) return "a tensor that is no protobuf";
    const std::string which = "tensor '" + name + "'";
    if (external) return which + " keeps its data in another file (not taken)";
    if (dims > kMaxDims) return which + " has " + std::to_string(dims) + " dimensions (at most " + std::to_string(kMaxDims) + ")";
    if (bad_dim) return which + " declares a negative or too large shape";
    ElementType t;
    if (!element_type(type, t)) return which + " has an unknown data type " + std::to_string(type);
    values[6] = strings;
    for (std::uint32_t field : {4u, 5u, 6u, 7u, 10u, 11u}) {
        if (values[field] == 0) continue;
        if (field != t.typed_field) return which + " holds values in a field its type does not use";
        typed_field_seen = 1;
        typed_values = values[field];
    }
    if (has_raw && typed_field_seen) return which + " holds both raw and typed data";
    if (has_raw) {
        if (t.raw_size == 0) return which + " holds strings as raw data";
        if (raw_length != elements * static_cast<std::uint64_t>(t.raw_size))
            return which + " declares " + std::to_string(elements) + " elements (" +
                   std::to_string(elements * static_cast<std::uint64_t>(t.raw_size)) + " bytes) but holds " +
                   std::to_string(raw_length) + " bytes";
        if ((type == 6 || type == 7) && !raw_integers_ok(raw, raw_length, t.raw_size))
            return which + " holds an integer beyond +-2^24 (a size or an axis OpenCV would allocate by)";
        return "";
    }
    if (!values_ok) return which + " holds an integer beyond +-2^24 (a size or an axis OpenCV would allocate by)";
    const std::uint64_t expected = elements * static_cast<std::uint64_t>(t.values_per_element);
    if (typed_values != expected)
        return which + " declares " + std::to_string(elements) + " elements but holds " + std::to_string(typed_values) + " values";
    return "";
}

// An AttributeProto: its tensors (t 5, tensors 10, sparse 22 / 23) and graphs (g 6, graphs 11).
std::string attribute_problem(const std::uint8_t *data, std::size_t size, int depth)
{
    Message m(data, size);
    Field f;
    while (m.next(f)) {
        if (f.wire != kBytes) continue;
        std::string problem;
        if (f.number == 5 || f.number == 10) problem = tensor_problem(f.bytes, f.length);
        else if (f.number == 6 || f.number == 11) problem = graph_problem(f.bytes, f.length, depth + 1);
        else if (f.number == 22 || f.number == 23) problem = "a sparse tensor attribute (not taken)";
        if (!problem.empty()) return problem;
    }
    return m.ok ? "" : "an attribute that is no protobuf";
}

// A NodeProto: its attributes (5).
std::string node_problem(const std::uint8_t *data, std::size_t size, int depth)
{
    Message m(data, size);
    Field f;
    while (m.next(f)) {
        if (f.number != 5) continue;
        if (f.wire != kBytes) return "a node attribute of the wrong wire type";
        const std::string problem = attribute_problem(f.bytes, f.length, depth);
        if (!problem.empty()) return problem;
    }
    return m.ok ? "" : "a node that is no protobuf";
}

// A GraphProto: its nodes (1), initializers (5) and sparse initializers (15).
std::string graph_problem(const std::uint8_t *data, std::size_t size, int depth)
{
    if (depth > kMaxDepth) return "graphs nested deeper than " + std::to_string(kMaxDepth);
    Message m(data, size);
    Field f;
    while (m.next(f)) {
        if (f.number != 1 && f.number != 5 && f.number != 15) continue;
        if (f.wire != kBytes) return "a graph field of the wrong wire type";
        const std::string problem = f.number == 1   ? node_problem(f.bytes, f.length, depth)
                                    : f.number == 5 ? tensor_problem(f.bytes, f.length)
                                                    : "a sparse initializer (not taken)";
        if (!problem.empty()) return problem;
    }
    return m.ok ? "" : "a graph that is no protobuf";
}

// A FunctionProto: its nodes (7).
std::string function_problem(const std::uint8_t *data, std::size_t size)
{
    Message m(data, size);
    Field f;
    while (m.next(f)) {
        if (f.number != 7) continue;
        if (f.wire != kBytes) return "a function node of the wrong wire type";
        const std::string problem = node_problem(f.bytes, f.length, 1);
        if (!problem.empty()) return problem;
    }
    return m.ok ? "" : "a function that is no protobuf";
}

}  // namespace

std::string onnx_model_problem(const std::uint8_t *data, std::size_t size)
{
    Message m(data, size);
    Field f;
    bool graph = false;
    while (m.next(f)) {  // ModelProto: graph 7, functions 25
        if (f.number != 7 && f.number != 25) continue;
        if (f.wire != kBytes) return "not an ONNX model (its graph field has the wrong wire type)";
        if (f.number == 7) graph = true;
        const std::string problem = f.number == 7 ? graph_problem(f.bytes, f.length, 0) : function_problem(f.bytes, f.length);
        if (!problem.empty()) return problem;
    }
    if (!m.ok) return "not an ONNX model (no protobuf)";
    if (!graph) return "not an ONNX model (no graph)";
    return "";
}

}  // namespace hkf_estimator
