#include "rownav/io/row_labels.hpp"

#include "rownav/io/csv.hpp"

namespace rownav::io {

std::map<std::int64_t, RowLabel> read_row_labels(const std::filesystem::path& file) {
  CsvReader csv(file);
  std::map<std::int64_t, RowLabel> out;
  if (!csv.next()) csv.fail("empty label file");
  csv.expect_header({"frame", "left_x0", "left_y0", "left_x1", "left_y1", "right_x0", "right_y0",
                     "right_x1", "right_y1"});
  static constexpr const char* kCols[] = {"left_x0",  "left_y0",  "left_x1",  "left_y1",
                                          "right_x0", "right_y0", "right_x1", "right_y1"};
  while (csv.next()) {
    csv.expect_size(9);
    double v[8];
    for (std::size_t i = 0; i < 8; ++i) v[i] = csv.number(i + 1, kCols[i]);
    RowLabel l;
    l.left = {{v[0], v[1]}, {v[2], v[3]}};
    l.right = {{v[4], v[5]}, {v[6], v[7]}};
    if (l.left.length() <= 0.0 || l.right.length() <= 0.0) csv.fail("degenerate label segment");
    out[csv.integer(0, "frame")] = l;  // a frame saved twice keeps its last label (data README)
  }
  return out;
}

}  // namespace rownav::io
