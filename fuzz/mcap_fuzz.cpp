// ROS 2 bags: io::read_mcap_recording (MCAP records, chunks, CDR messages) + every cloud.
#include "fuzz_common.hpp"
#include "rownav/io/bag_recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rownav::fuzz::input_file("mcap", data, size);
  rownav::fuzz::expect_clean(file.string(), [&] {
    const rownav::io::Recording rec = rownav::io::read_mcap_recording(file);
    for (std::size_t i = 0; i < rec.cloud_count(); ++i) (void)rec.cloud(i);
  });
  return 0;
}
