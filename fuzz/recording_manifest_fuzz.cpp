// A recording's manifest.yaml (io::read_recording of a directory holding only the manifest).
#include "fuzz_common.hpp"
#include "rownav/io/recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = rownav::fuzz::scratch() / "rec";
  rownav::fuzz::write_bytes(dir / "manifest.yaml", data, size);
  rownav::fuzz::expect_clean(dir.string(), [&] { (void)rownav::io::read_recording(dir); });
  return 0;
}
