#pragma once
// A tiny Darknet YOLO network the tests write themselves (no downloads): 32 x 32 input, an 8 x 8
// max-pool to a 4 x 4 grid, one 1 x 1 convolution and a [yolo] layer with one 8 x 8 anchor and two
// classes. Objectness rises with green + blue and falls with red; class 0 follows green, class 1
// blue: a pure green block filling a grid cell is one class-0 box of that cell, a blue one class 1.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace rownav::vision::test {

inline const char* tiny_yolo_cfg() {
  return "[net]\nwidth=32\nheight=32\nchannels=3\n\n"
         "[maxpool]\nsize=8\nstride=8\npadding=0\n\n"
         "[convolutional]\nfilters=7\nsize=1\nstride=1\npad=0\nactivation=linear\n\n"
         "[yolo]\nmask=0\nanchors=8,8\nclasses=2\nnum=1\n";
}

/// Darknet weights: header (major, minor, revision, 64-bit images seen), then the convolution's
/// 7 biases and 7 x 3 weights (filter-major), float32. `bytes` > 0 truncates the file there.
inline void write_tiny_yolo(const std::filesystem::path& cfg, const std::filesystem::path& weights,
                            std::size_t bytes = 0) {
  std::ofstream(cfg) << tiny_yolo_cfg();
  std::ofstream w(weights, std::ios::binary);
  const std::int32_t header[3] = {0, 2, 0};
  const std::uint64_t seen = 0;
  std::string data(reinterpret_cast<const char*>(header), sizeof header);
  data.append(reinterpret_cast<const char*>(&seen), sizeof seen);
  // outputs: tx, ty, tw, th, objectness, class 0, class 1
  std::vector<float> v{0,   0,  0,  0, -3, -5, -5,  // biases
                       0,   0,  0,  0, 0,  0,  0,
                       0,   0,  0,  0, 0,  // box: centre of the cell, anchor size
                       -10, 10, 10,        // objectness from R, G, B
                       0,   10, 0,         // class 0: green
                       0,   0,  10};       // class 1: blue
  data.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
  if (bytes > 0) data.resize(bytes);
  w.write(data.data(), static_cast<std::streamsize>(data.size()));
}

}  // namespace rownav::vision::test
