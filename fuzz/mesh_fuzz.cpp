// Meshes through assimp (io::read_mesh). The first byte picks the format, so one corpus
// covers OBJ, STL (ascii and binary) and Collada; the rest is the file.
#include <array>

#include "fuzz_common.hpp"
#include "rownav/io/mesh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::array<const char*, 3> kExt = {"obj", "stl", "dae"};
  if (size < 1) return 0;
  const auto file = rownav::fuzz::input_file(kExt[data[0] % kExt.size()], data + 1, size - 1);
  rownav::fuzz::expect_clean(
      file.string(), [&] { (void)rownav::io::read_mesh(file, rownav::sim::SurfaceClass::ground); });
  return 0;
}
