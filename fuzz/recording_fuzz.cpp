// Whole recording directories (io::read_recording, then every cloud it lists). The input is a
// little archive: the text up to the first "=== <file>\n" line is manifest.yaml, each such
// line starts one of the recording's files (names outside kFiles are skipped, so nothing is
// written outside the scratch directory).
#include <algorithm>
#include <array>
#include <string_view>

#include "fuzz_common.hpp"
#include "rownav/io/recording.hpp"

namespace {

constexpr std::array<std::string_view, 13> kFiles = {
    "manifest.yaml",    "lidar/frames.csv", "lidar/scans.csv",  "lidar/000000.pcd",
    "lidar/000001.pcd", "encoders.csv",     "imu.csv",          "gnss.csv",
    "ground_truth.csv", "field/rows.csv",   "field/plants.csv", "inputs.csv",
    "lidar/000002.pcd"};

void write_archive(const std::filesystem::path& dir, std::string_view text) {
  std::string_view name = "manifest.yaml";
  while (true) {
    const auto mark = text.find("\n=== ");
    const std::string_view body = text.substr(0, mark);
    if (std::find(kFiles.begin(), kFiles.end(), name) != kFiles.end())
      rownav::fuzz::write_bytes(dir / name, reinterpret_cast<const std::uint8_t*>(body.data()),
                                body.size());
    if (mark == std::string_view::npos) return;
    text.remove_prefix(mark + 5);
    const auto eol = text.find('\n');
    name = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = rownav::fuzz::scratch() / "rec";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::filesystem::create_directories(dir);
  write_archive(dir, std::string_view(reinterpret_cast<const char*>(data), size));
  rownav::fuzz::expect_clean(dir.string(), [&] {
    const rownav::io::Recording rec = rownav::io::read_recording(dir);
    for (std::size_t i = 0; i < rec.cloud_count(); ++i) (void)rec.cloud(i);
  });
  return 0;
}
