#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rownav/io/input_error.hpp"
#include "rownav/io/row_labels.hpp"

namespace rownav::io {
namespace {

TEST(RowLabels, ReadsTheRealCornLabels) {
  const auto labels = read_row_labels(std::filesystem::path(ROWNAV_SHARED_DATA) / "corn_rows_2d/labels.csv");
  EXPECT_EQ(labels.size(), 1630u);  // the data README: 1630 distinct labelled steps
  const RowLabel& first = labels.at(1);
  EXPECT_NEAR(first.left.a.x(), 0.3218, 1e-9);
  EXPECT_NEAR(first.right.b.y(), -0.2711, 1e-9);
  for (const auto& [frame, l] : labels) {
    EXPECT_GT(l.left.a.y() + l.left.b.y(), l.right.a.y() + l.right.b.y()) << frame;  // left is left
  }
}

TEST(RowLabels, MalformedLineIsOneLineError) {
  const auto f = std::filesystem::temp_directory_path() / "rownav_bad_labels.csv";
  {
    std::ofstream o(f);
    o << "frame,left_x0,left_y0,left_x1,left_y1,right_x0,right_y0,right_x1,right_y1\n"
      << "1,0.3,0.3,1.0,0.3,0.3,-0.3,1.0,-0.3\n"
      << "2,0.3,abc,1.0,0.3,0.3,-0.3,1.0,-0.3\n";
  }
  try {
    read_row_labels(f);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rownav_bad_labels.csv:3:"), std::string::npos) << e.what();
  }
  std::filesystem::remove(f);
}

}  // namespace
}  // namespace rownav::io
