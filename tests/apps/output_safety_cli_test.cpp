// End to end: no rownav command deletes a file or folder it did not write (issue 13).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"

namespace rownav {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::rownav;
using test::TempDir;

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

const char* const kField =
    "kind: vineyard\nseed: 4\nvineyard:\n  rows: 4\n  row_length: 15.0\n  row_spacing: 2.0\n";

bool staging_left(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (const auto n = e.path().filename().string();
        n.find(".rownav-partial") != std::string::npos || n.find(".rownav-old") != std::string::npos)
      return true;
  return false;
}

TEST(OutputSafety, RunRefusesAUsersFolderAndTheCurrentFolderBeforeSimulating) {
  TempDir t("outsafe");
  write(t / "field.yaml", kField);
  write(t / "mine/data.csv", "1,2\n");
  const std::string args =
      " --field field.yaml --robot " ROWNAV_SOURCE_DIR "/config/robots/skid_steer.yaml"
      " --mission " ROWNAV_SOURCE_DIR "/config/missions/serve_all.yaml --quiet --overwrite";
  for (const std::string& out : std::vector<std::string>{"mine", ".", "./", t.path().string()}) {
    const auto r = rownav(t.path(), "run --out " + out + args);
    EXPECT_EQ(r.code, 2) << out << ": " << r.err;
    EXPECT_NE(r.err.find("rownav: error: "), std::string::npos) << r.err;
    EXPECT_EQ(read_file(t / "mine/data.csv"), "1,2\n") << out;
    EXPECT_TRUE(fs::exists(t / "field.yaml")) << out;
  }
  const auto demo = rownav(t.path(), "demo --out mine --overwrite --config-dir " ROWNAV_SOURCE_DIR
                                     "/config --quiet");
  EXPECT_EQ(demo.code, 2) << demo.err;
  EXPECT_EQ(read_file(t / "mine/data.csv"), "1,2\n");
  EXPECT_FALSE(staging_left(t.path()));
}

TEST(OutputSafety, SimKeepsAUsersPartialFolderAndRefusesToOverwriteANonRecording) {
  TempDir t("outsafe");
  write(t / "field.yaml", kField);
  write(t / "rec.partial/notes.txt", "mine");
  write(t / "photos/a.jpg", "jpeg");
  const std::string sim = "sim --field field.yaml --lidar lms_1081 --quiet --max-time 5 ";
  auto r = rownav(t.path(), sim + "--out rec");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(t / "rec.partial/notes.txt"), "mine");
  r = rownav(t.path(), sim + "--out photos --overwrite");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not written by rownav"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(t / "photos/a.jpg"), "jpeg");
  r = rownav(t.path(), sim + "--out rec");  // its own recording: only with --overwrite
  EXPECT_EQ(r.code, 2);
  r = rownav(t.path(), sim + "--out rec --overwrite");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(staging_left(t.path()));
}

TEST(OutputSafety, DetectKeepsAUsersPartialFileAndAnExistingOutput) {
  TempDir t("outsafe");
  write(t / "pts.csv", "x,y\n1,0.9\n2,0.9\n3,0.9\n1,-0.9\n2,-0.9\n3,-0.9\n");
  write(t / "v.json.partial", "mine");
  write(t / "old.json", "keep");
  auto r = rownav(t.path(), "detect --detector baseline --in pts.csv --out v.json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(t / "v.json.partial"), "mine");
  r = rownav(t.path(), "detect --detector baseline --in pts.csv --out old.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(read_file(t / "old.json"), "keep");
  r = rownav(t.path(), "detect --detector baseline --in pts.csv --out old.json --overwrite");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(read_file(t / "old.json"), "keep");
  EXPECT_FALSE(staging_left(t.path()));
}

TEST(OutputSafety, CtrlCDuringSimLeavesNoPartialOutput) {
  TempDir t("outsafe");
  // A 3D LiDAR over 60 m rows: several seconds of work, interrupted after one.
  write(t / "field.yaml",
        "kind: vineyard\nseed: 4\nvineyard:\n  rows: 4\n  row_length: 60.0\n  row_spacing: 2.0\n");
  for (const char* sig : {"INT", "TERM"}) {
    const std::string cmd = "cd '" + t.path().string() + "' && timeout --preserve-status -s " +
                            sig + " 1 '" ROWNAV_BINARY "' sim --field field.yaml --quiet --out rec"
                            " > /dev/null 2>&1";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_NE(WEXITSTATUS(status), 0) << sig << ": the drive finished before the signal";
    EXPECT_FALSE(fs::exists(t / "rec")) << sig;
    EXPECT_FALSE(staging_left(t.path())) << sig;
  }
}

}  // namespace
}  // namespace rownav
