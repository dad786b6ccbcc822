// test_onnx_check.cpp - the model file check (estimator/src/models/onnx_check.cpp) on models written here
// byte by byte in protobuf's wire format: one whole tensor taken in each place a tensor may stand (an
// initializer, a node's attribute, a subgraph's initializer), then each rule broken alone - data shorter or
// longer than the shape, a negative dimension, one beyond 2^31 beside a zero, too many dimensions, an
// unknown type, data of the wrong field, raw and typed data together, external data, an integer beyond
// +-2^24 (raw and typed) and the extremes that mean "to the end", a cut-off file.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cstdint>
#include <string>
#include <vector>

#include "onnx_check.hpp"

extern "C" {
#include <cmocka.h>
}

namespace {

using Bytes = std::vector<std::uint8_t>;

void varint(Bytes &out, std::uint64_t v)
{
    while (v >= 0x80) {
        out.push_back(static_cast<std::uint8_t>(v | 0x80));
        v >>= 7;
    }
    out.push_back(static_cast<std::uint8_t>(v));
}

void key(Bytes &out, int field, int wire) { varint(out, static_cast<std::uint64_t>(field) << 3 | static_cast<unsigned>(wire)); }

void number(Bytes &out, int field, std::int64_t v)
{
    key(out, field, 0);
    varint(out, static_cast<std::uint64_t>(v));
}

void bytes(Bytes &out, int field, const Bytes &b)
{
    key(out, field, 2);
    varint(out, b.size());
    out.insert(out.end(), b.begin(), b.end());
}

Bytes text(const std::string &s) { return Bytes(s.begin(), s.end()); }

// A TensorProto: dims, data_type, name, raw_data of raw_length bytes (when >= 0), and any extra fields.
Bytes tensor(const std::vector<std::int64_t> &dims, int type, long raw_length, const Bytes &extra = {})
{
    Bytes t;
    for (std::int64_t d : dims) number(t, 1, d);
    number(t, 2, type);
    bytes(t, 8, text("w"));
    if (raw_length >= 0) bytes(t, 9, Bytes(static_cast<size_t>(raw_length), 0));
    t.insert(t.end(), extra.begin(), extra.end());
    return t;
}

// A ModelProto whose graph holds the tensor as an initializer.
Bytes model_with_initializer(const Bytes &t)
{
    Bytes graph, model;
    bytes(graph, 5, t);
    number(model, 1, 8);  // ir_version
    bytes(model, 7, graph);
    return model;
}

std::string problem(const Bytes &model) { return hkf_estimator::onnx_model_problem(model.data(), model.size()); }

std::string initializer_problem(const Bytes &t) { return problem(model_with_initializer(t)); }

void test_whole_tensors_taken(void **)
{
    assert_string_equal(initializer_problem(tensor({2, 3, 1, 1}, 1, 24)).c_str(), "");  // FLOAT raw
    assert_string_equal(initializer_problem(tensor({0, 5}, 1, 0)).c_str(), "");         // no elements, no data
    Bytes packed;  // FLOAT typed: 6 floats packed
    bytes(packed, 4, Bytes(24, 0));
    assert_string_equal(initializer_problem(tensor({6}, 1, -1, packed)).c_str(), "");
    // a node's attribute tensor (Constant's value), and an initializer of a subgraph inside an attribute
    Bytes attribute, node, graph, model, inner_graph, inner_attribute, inner_node;
    bytes(attribute, 1, text("value"));
    bytes(attribute, 5, tensor({3}, 7, 24));
    bytes(node, 5, attribute);
    bytes(graph, 1, node);
    bytes(inner_graph, 5, tensor({4}, 1, 16));
    bytes(inner_attribute, 6, inner_graph);
    bytes(inner_node, 5, inner_attribute);
    bytes(graph, 1, inner_node);
    bytes(model, 7, graph);
    assert_string_equal(problem(model).c_str(), "");
}

void test_data_against_shape(void **)
{
    assert_true(initializer_problem(tensor({2, 3}, 1, 20)).find("declares 6 elements (24 bytes) but holds 20 bytes") !=
                std::string::npos);
    assert_true(initializer_problem(tensor({2, 3}, 1, 28)).find("but holds 28 bytes") != std::string::npos);
    assert_true(initializer_problem(tensor({2, 3}, 1, -1)).find("declares 6 elements but holds 0 values") !=
                std::string::npos);  // no data at all
    Bytes both;
    bytes(both, 4, Bytes(24, 0));
    assert_true(initializer_problem(tensor({6}, 1, 24, both)).find("both raw and typed") != std::string::npos);
    Bytes wrong;
    bytes(wrong, 7, Bytes{1, 2, 3, 4, 5, 6});  // int64_data for a FLOAT
    assert_true(initializer_problem(tensor({6}, 1, -1, wrong)).find("a field its type does not use") != std::string::npos);
}

void test_shape_bounds(void **)
{
    assert_true(initializer_problem(tensor({-1, 4}, 1, 0)).find("negative or too large") != std::string::npos);
    // one dimension beyond 2^31, the product 0 (a zero beside it): refused by the dimension's own bound
    assert_true(initializer_problem(tensor({0, (1LL << 31) + 1}, 1, 0)).find("negative or too large") != std::string::npos);
    assert_string_equal(initializer_problem(tensor({0, 1LL << 31}, 1, 0)).c_str(), "");  // at the bound
    assert_true(initializer_problem(tensor({1 << 30, 1 << 30, 3, 3}, 1, 64)).find("negative or too large") != std::string::npos);
    assert_true(initializer_problem(tensor(std::vector<std::int64_t>(17, 1), 1, 4)).find("17 dimensions") != std::string::npos);
    assert_true(initializer_problem(tensor({1}, 99, 4)).find("unknown data type 99") != std::string::npos);
}

void test_integers_bounded(void **)
{
    auto int64_raw = [](std::int64_t v) {
        Bytes b;
        for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(v) >> (8 * i)));
        Bytes t;
        number(t, 1, 1);
        number(t, 2, 7);
        bytes(t, 9, b);
        return t;
    };
    assert_string_equal(initializer_problem(int64_raw(1 << 24)).c_str(), "");
    assert_string_equal(initializer_problem(int64_raw(-(1 << 24))).c_str(), "");
    assert_string_equal(initializer_problem(int64_raw(INT64_MAX)).c_str(), "");  // "to the end"
    assert_string_equal(initializer_problem(int64_raw(INT64_MIN)).c_str(), "");
    assert_true(initializer_problem(int64_raw((1 << 24) + 1)).find("beyond +-2^24") != std::string::npos);
    assert_true(initializer_problem(int64_raw(100000000000000000LL)).find("beyond +-2^24") != std::string::npos);
    Bytes typed;  // int32_data, packed: 5 then 2^25
    Bytes values;
    varint(values, 5);
    varint(values, 1 << 25);
    bytes(typed, 5, values);
    assert_true(initializer_problem(tensor({2}, 6, -1, typed)).find("beyond +-2^24") != std::string::npos);
}

void test_not_taken(void **)
{
    Bytes external;
    number(external, 14, 1);  // data_location EXTERNAL
    assert_true(initializer_problem(tensor({2}, 1, -1, external)).find("another file") != std::string::npos);
    Bytes segment;
    bytes(segment, 3, Bytes{8, 0, 16, 1});
    assert_true(initializer_problem(tensor({2}, 1, 8, segment)).find("segments") != std::string::npos);
    Bytes model = model_with_initializer(tensor({2, 3}, 1, 24));
    model.resize(model.size() - 5);  // cut off
    assert_true(problem(model).find("not a readable ONNX model") != std::string::npos);
    Bytes no_graph;
    number(no_graph, 1, 8);
    assert_true(problem(no_graph).find("no graph") != std::string::npos);
    const Bytes noise = {0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x01};
    assert_true(problem(noise).find("not a readable ONNX model") != std::string::npos);
}

// A model whose one node holds a `value` attribute with its field `number_of_field` (5: a tensor, 6: a graph)
// given once per entry of `fields`, which protobuf would merge.
Bytes model_with_attribute_fields(int number_of_field, const std::vector<Bytes> &fields)
{
    Bytes attribute, node, graph, model;
    bytes(attribute, 1, text("value"));
    for (const Bytes &f : fields) bytes(attribute, number_of_field, f);
    bytes(node, 5, attribute);
    bytes(graph, 1, node);
    bytes(model, 7, graph);
    return model;
}

// Hardening round 6, item 1: a singular message field given twice is merged by protobuf (repeated fields
// joined, scalars from the last), so each occurrence passing alone is not enough. A Constant's tensor given as
// INT8 dims [N] with N int32_data, then FLOAT dims [1] with 4 bytes of raw_data, reads as FLOAT dims [N, 1]
// with 4 bytes: OpenCV copied 4N bytes out of them (SIGSEGV while loading). Checked as the merge, refused.
void test_merged_tensor_refused(void **)
{
    const int n = 1000;
    Bytes int8_values, int8_part;
    for (int i = 0; i < n; ++i) varint(int8_values, 1);
    number(int8_part, 1, n);
    number(int8_part, 2, 3);  // INT8
    bytes(int8_part, 5, int8_values);
    const Bytes float_part = tensor({1}, 1, 4);
    assert_string_equal(initializer_problem(int8_part).c_str(), "");   // alone: whole
    assert_string_equal(initializer_problem(float_part).c_str(), "");  // alone: whole
    const std::string merged = problem(model_with_attribute_fields(5, {int8_part, float_part}));
    assert_true(merged.find("both raw and typed") != std::string::npos ||
                merged.find("a field its type does not use") != std::string::npos);
}

// The model's graph, an attribute's graph and a tensor's dims, each given in two occurrences: checked as merged.
void test_merged_occurrences(void **)
{
    // two occurrences of the model's graph: a tensor is per occurrence of `initializer` (repeated), so two whole
    // ones stay whole
    Bytes first, second, split;
    bytes(first, 5, tensor({2}, 1, 8));
    bytes(second, 5, tensor({3}, 1, 12));
    number(split, 1, 8);
    bytes(split, 7, first);
    bytes(split, 7, second);
    assert_string_equal(problem(split).c_str(), "");
    // a graph given twice inside an attribute (g): its halves merged, and what the merge holds is checked
    Bytes half;
    bytes(half, 5, tensor({2, 3}, 1, 20));  // short: refused in whichever half it stands
    assert_true(problem(model_with_attribute_fields(6, {first, half})).find("but holds 20 bytes") != std::string::npos);
    // a tensor's dims split across two occurrences: joined ([2, 3]), with the last's 24 bytes: whole
    Bytes dims_a, dims_b;
    number(dims_a, 1, 2);
    number(dims_b, 1, 3);
    number(dims_b, 2, 1);
    Bytes short_b = dims_b;  // the same with 4 bytes: [2, 3] declared, refused
    bytes(dims_b, 9, Bytes(24, 0));
    bytes(short_b, 9, Bytes(4, 0));
    assert_string_equal(problem(model_with_attribute_fields(5, {dims_a, dims_b})).c_str(), "");
    assert_true(problem(model_with_attribute_fields(5, {dims_a, short_b}))
                    .find("declares 6 elements (24 bytes) but holds 4 bytes") != std::string::npos);
}

// Round 6's own review: nesting. Graphs inside attributes inside graphs are checked to 16 levels and refused
// beyond, without recursing further (a file of 10,000 nested If branches: no stack overflow).
void test_nesting_bounded(void **)
{
    auto nested = [](int depth) {
        Bytes graph;
        bytes(graph, 5, tensor({2}, 1, 8));
        for (int level = 0; level < depth; ++level) {
            Bytes attribute, node, outer;
            bytes(attribute, 1, text("then_branch"));
            bytes(attribute, 6, graph);
            bytes(node, 5, attribute);
            bytes(outer, 1, node);
            graph = outer;
        }
        Bytes model;
        bytes(model, 7, graph);
        return model;
    };
    assert_string_equal(problem(nested(16)).c_str(), "");
    assert_true(problem(nested(17)).find("graphs nested deeper than 16") != std::string::npos);
    assert_true(problem(nested(10000)).find("graphs nested deeper than 16") != std::string::npos);
}

}  // namespace

int main()
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_whole_tensors_taken), cmocka_unit_test(test_data_against_shape),
        cmocka_unit_test(test_shape_bounds),        cmocka_unit_test(test_integers_bounded),
        cmocka_unit_test(test_not_taken),           cmocka_unit_test(test_merged_occurrences),
        cmocka_unit_test(test_merged_tensor_refused),
        cmocka_unit_test(test_nesting_bounded),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
