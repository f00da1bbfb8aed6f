// CSV row layouts (io::read_layout by extension -> read_csv_layout), default limits.
#include "fuzz_common.hpp"
#include "rownav/io/layout_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = rownav::fuzz::input_file("csv", data, size);
  rownav::fuzz::expect_clean(file.string(), [&] { (void)rownav::io::read_layout(file); });
  return 0;
}
