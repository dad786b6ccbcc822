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

std::string graph_problem(const std::uint8_t *data, std::size_t size, int depth);

// A singular message field given more than once is read by protobuf (and so by OpenCV) as one message, the
// occurrences merged: repeated fields joined, scalars from the last. Parsing the occurrences' bytes one after
// the other gives exactly that merge, so each such field is gathered here and checked as one.
struct Merged {
    std::string bytes;
    bool present = false;

    void add(const Field &f)
    {
        bytes.append(reinterpret_cast<const char *>(f.bytes), f.length);
        present = true;
    }
    const std::uint8_t *data() const { return reinterpret_cast<const std::uint8_t *>(bytes.data()); }
};

// What a TensorProto declares and holds, as its fields were read.
struct TensorFields {
    std::string name;
    std::uint64_t dims = 0, elements = 1, type = 0;
    std::uint64_t values[12] = {};  // per typed field number (4, 5, 6, 7, 10, 11): values held
    bool bad_dim = false, has_raw = false, external = false, integers_ok = true;
    const std::uint8_t *raw = nullptr;  // raw_data: a scalar field, so its last occurrence is the one read
    std::size_t raw_length = 0;
};

// The dims field (int64, packed or not) added to t: "" or why the field is malformed.
std::string add_dimensions(const Field &f, TensorFields &t)
{
    const auto dimension = [&t](std::uint64_t d) {
        ++t.dims;
        if (static_cast<std::int64_t>(d) < 0 || d > kMaxDim) t.bad_dim = true;
        else if (!t.bad_dim && d != 0 && t.elements > kMaxElements / d) t.bad_dim = true;
        else t.elements *= d;
    };
    if (f.wire == kVarint) {
        dimension(f.value);
        return "";
    }
    if (f.wire != kBytes) return "dimensions of the wrong wire type";
    Message packed(f.bytes, f.length);
    std::uint64_t d;
    while (packed.at != packed.end) {
        if (!packed.varint(d)) return "a dimension list that is no protobuf";
        dimension(d);
    }
    return "";
}

// One field of a TensorProto into t: "" or why it is malformed or not taken.
std::string read_tensor_field(const Field &f, TensorFields &t)
{
    switch (f.number) {
    case 1: return add_dimensions(f, t);
    case 2:
        if (f.wire != kVarint) return "a data type of the wrong wire type";
        t.type = f.value;
        return "";
    case 3: return "tensor '" + t.name + "' is split into segments (not taken)";
    case 8:
        if (f.wire == kBytes) t.name.assign(reinterpret_cast<const char *>(f.bytes), f.length < 80 ? f.length : 80);
        return "";
    case 9:
        if (f.wire != kBytes) return "raw data of the wrong wire type";
        t.has_raw = true;
        t.raw = f.bytes;
        t.raw_length = f.length;
        return "";
    case 6:  // string_data
        if (f.wire != kBytes) return "string data of the wrong wire type";
        ++t.values[6];
        return "";
    case 4: case 5: case 7: case 10: case 11:
        if (!count_values(f, t.values[f.number])) return "typed data that is no protobuf";
        if ((f.number == 5 || f.number == 7) && !typed_integers_ok(f)) t.integers_ok = false;
        return "";
    case 13: t.external = true; return "";
    case 14:
        if (f.wire == kVarint && f.value == 1) t.external = true;
        return "";
    default: return "";
    }
}

// Whether what t holds is what it declares: "" or why not.
std::string tensor_data_problem(const TensorFields &t)
{
    const std::string which = "tensor '" + t.name + "'", beyond = " holds an integer beyond +-2^24 (a size or an axis "
                                                                  "OpenCV would allocate by)";
    if (t.external) return which + " keeps its data in another file (not taken)";
    if (t.dims > kMaxDims) return which + " has " + std::to_string(t.dims) + " dimensions (at most " + std::to_string(kMaxDims) + ")";
    if (t.bad_dim) return which + " declares a negative or too large shape";
    ElementType e;
    if (!element_type(t.type, e)) return which + " has an unknown data type " + std::to_string(t.type);
    std::uint64_t typed_values = 0;
    bool typed = false;
    for (std::uint32_t field : {4u, 5u, 6u, 7u, 10u, 11u}) {
        if (t.values[field] == 0) continue;
        if (field != e.typed_field) return which + " holds values in a field its type does not use";
        typed = true;
        typed_values = t.values[field];
    }
    if (t.has_raw && typed) return which + " holds both raw and typed data";
    if (t.has_raw) {
        const std::uint64_t bytes = t.elements * static_cast<std::uint64_t>(e.raw_size);
        if (e.raw_size == 0) return which + " holds strings as raw data";
        if (t.raw_length != bytes)
            return which + " declares " + std::to_string(t.elements) + " elements (" + std::to_string(bytes) +
                   " bytes) but holds " + std::to_string(t.raw_length) + " bytes";
        if ((t.type == 6 || t.type == 7) && !raw_integers_ok(t.raw, t.raw_length, e.raw_size)) return which + beyond;
        return "";
    }
    if (!t.integers_ok) return which + beyond;
    if (typed_values != t.elements * static_cast<std::uint64_t>(e.values_per_element))
        return which + " declares " + std::to_string(t.elements) + " elements but holds " + std::to_string(typed_values) + " values";
    return "";
}

std::string tensor_problem(const std::uint8_t *data, std::size_t size)
{
    Message m(data, size);
    Field f;
    TensorFields t;
    while (m.next(f)) {
        const std::string problem = read_tensor_field(f, t);
        if (!problem.empty()) return problem;
    }
    if (!m.ok) return "a tensor that is no protobuf";
    return tensor_data_problem(t);
}

// An AttributeProto: its tensors (t 5, singular: its occurrences merged; tensors 10; sparse 22 / 23) and
// graphs (g 6, singular: merged; graphs 11).
std::string attribute_problem(const std::uint8_t *data, std::size_t size, int depth)
{
    Message m(data, size);
    Field f;
    Merged t, g;
    while (m.next(f)) {
        if (f.wire != kBytes) continue;
        std::string problem;
        if (f.number == 5) t.add(f);
        else if (f.number == 6) g.add(f);
        else if (f.number == 10) problem = tensor_problem(f.bytes, f.length);
        else if (f.number == 11) problem = graph_problem(f.bytes, f.length, depth + 1);
        else if (f.number == 22 || f.number == 23) problem = "a sparse tensor attribute (not taken)";
        if (!problem.empty()) return problem;
    }
    if (!m.ok) return "an attribute that is no protobuf";
    if (t.present) {
        const std::string problem = tensor_problem(t.data(), t.bytes.size());
        if (!problem.empty()) return problem;
    }
    return g.present ? graph_problem(g.data(), g.bytes.size(), depth + 1) : "";
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
    Merged graph;  // ModelProto: graph 7 (singular: its occurrences merged), functions 25
    while (m.next(f)) {
        if (f.number != 7 && f.number != 25) continue;
        if (f.wire != kBytes) return "not a readable ONNX model (its graph field has the wrong wire type)";
        if (f.number == 7) {
            graph.add(f);
            continue;
        }
        const std::string problem = function_problem(f.bytes, f.length);
        if (!problem.empty()) return problem;
    }
    if (!m.ok) return "not a readable ONNX model (no protobuf)";
    if (!graph.present) return "not a readable ONNX model (no graph)";
    return graph_problem(graph.data(), graph.bytes.size(), 0);
}

}  // namespace hkf_estimator
