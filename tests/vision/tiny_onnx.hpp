#pragma once
// A tiny ONNX detector the tests encode themselves (protobuf by hand, no downloads): input
// "images" [1, 3, 32, 32] -> GlobalAveragePool -> Flatten -> Gemm(W [7, 3]^T, b [7]) -> "rows"
// [1, 7], one YOLO row: a 8 x 8 px box at the centre of the 32 px input, objectness = mean
// green + mean blue, class 0 = mean green, class 1 = mean blue (boxes in input pixels).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace rownav::vision::test {

namespace pb {
inline void varint(std::string& out, std::uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<char>((v & 0x7f) | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<char>(v));
}
inline void tag(std::string& out, int field, int wire) {
  varint(out, std::uint64_t(field) << 3 | wire);
}
inline void field_varint(std::string& out, int field, std::uint64_t v) {
  tag(out, field, 0);
  varint(out, v);
}
inline void field_bytes(std::string& out, int field, const std::string& bytes) {
  tag(out, field, 2);
  varint(out, bytes.size());
  out += bytes;
}
}  // namespace pb

/// ValueInfoProto of a float tensor `name` with `dims`.
inline std::string value_info(const std::string& name, const std::vector<std::int64_t>& dims) {
  std::string shape;
  for (const auto d : dims) {
    std::string dim;
    pb::field_varint(dim, 1, static_cast<std::uint64_t>(d));  // dim_value
    pb::field_bytes(shape, 1, dim);
  }
  std::string tensor;
  pb::field_varint(tensor, 1, 1);  // elem_type FLOAT
  pb::field_bytes(tensor, 2, shape);
  std::string type;
  pb::field_bytes(type, 1, tensor);  // tensor_type
  std::string vi;
  pb::field_bytes(vi, 1, name);
  pb::field_bytes(vi, 2, type);
  return vi;
}

/// TensorProto initializer of floats.
inline std::string initializer(const std::string& name, const std::vector<std::int64_t>& dims,
                               const std::vector<float>& values) {
  std::string t;
  for (const auto d : dims) pb::field_varint(t, 1, static_cast<std::uint64_t>(d));
  pb::field_varint(t, 2, 1);  // FLOAT
  pb::field_bytes(t, 8, name);
  pb::field_bytes(t, 9,
                  std::string(reinterpret_cast<const char*>(values.data()), values.size() * 4));
  return t;
}

/// NodeProto; `int_attr` (optional): one INT attribute (name, value).
inline std::string node(const std::vector<std::string>& in, const std::string& out,
                        const std::string& op, const std::string& int_attr = "",
                        std::int64_t value = 0) {
  std::string n;
  for (const auto& i : in) pb::field_bytes(n, 1, i);
  pb::field_bytes(n, 2, out);
  pb::field_bytes(n, 3, op + "_node");
  pb::field_bytes(n, 4, op);
  if (!int_attr.empty()) {
    std::string a;
    pb::field_bytes(a, 1, int_attr);
    pb::field_varint(a, 3, static_cast<std::uint64_t>(value));
    pb::field_varint(a, 20, 2);  // AttributeType INT
    pb::field_bytes(n, 5, a);
  }
  return n;
}

inline void write_tiny_onnx(const std::filesystem::path& path) {
  // Gemm (transB = 1): rows = flat [1, 3] x W^T + b, W [7, 3]: one row of R, G, B weights an
  // output column (centre u, centre v, width, height, objectness, class 0, class 1).
  const std::vector<float> w{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // the box: biases only
                             0, 1, 1,                             // objectness: G + B
                             0, 1, 0,                             // class 0: G
                             0, 0, 1};                            // class 1: B
  const std::vector<float> b{16, 16, 8, 8, 0, 0, 0};
  std::string graph;
  pb::field_bytes(graph, 1, node({"images"}, "pooled", "GlobalAveragePool"));
  pb::field_bytes(graph, 1, node({"pooled"}, "flat", "Flatten"));
  pb::field_bytes(graph, 1, node({"flat", "W", "b"}, "rows", "Gemm", "transB", 1));
  pb::field_bytes(graph, 2, "tiny");
  pb::field_bytes(graph, 5, initializer("W", {7, 3}, w));
  pb::field_bytes(graph, 5, initializer("b", {7}, b));
  pb::field_bytes(graph, 11, value_info("images", {1, 3, 32, 32}));
  pb::field_bytes(graph, 12, value_info("rows", {1, 7}));
  std::string opset;
  pb::field_bytes(opset, 1, "");
  pb::field_varint(opset, 2, 11);
  std::string model;
  pb::field_varint(model, 1, 7);  // ir_version
  pb::field_bytes(model, 2, "rownav-test");
  pb::field_bytes(model, 7, graph);
  pb::field_bytes(model, 8, opset);
  std::ofstream(path, std::ios::binary)
      .write(model.data(), static_cast<std::streamsize>(model.size()));
}

}  // namespace rownav::vision::test
