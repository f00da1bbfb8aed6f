// PLY clouds through io::read_cloud (rownav's header pre-check, then PCL's PLYReader).
#include "fuzz_common.hpp"
#include "rownav/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rownav::fuzz::input_file("ply", data, size);
  rownav::fuzz::expect_clean(file.string(), [&] { (void)rownav::io::read_cloud(file); });
  return 0;
}
