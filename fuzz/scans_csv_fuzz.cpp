// CSV planar scans (io::read_scans_csv).
#include "fuzz_common.hpp"
#include "rownav/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rownav::fuzz::input_file("csv", data, size);
  rownav::fuzz::expect_clean(file.string(), [&] { (void)rownav::io::read_scans_csv(file); });
  return 0;
}
