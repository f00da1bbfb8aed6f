// io::OutputDir / io::OutputFile: rownav never deletes what it did not write (issue 13).
#include "rownav/io/safe_output.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>

#include "common/cli_runner.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::TempDir;

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

/// Every entry of `dir` whose name marks a rownav staging path.
std::vector<fs::path> staging_left(const fs::path& dir) {
  std::vector<fs::path> left;
  for (const auto& e : fs::directory_iterator(dir))
    if (const auto n = e.path().filename().string();
        n.find(".rownav-partial") != std::string::npos || n.find(".rownav-old") != std::string::npos)
      left.push_back(e.path());
  return left;
}

TEST(OutputDir, ANewFolderIsCreatedWithTheMarkerOnCommit) {
  TempDir t("safe");
  OutputDir out(t / "run", false, "run");
  EXPECT_FALSE(fs::exists(t / "run"));  // nothing at the target until commit
  write(out.staging() / "summary.json", "{}");
  out.commit();
  EXPECT_TRUE(is_rownav_output(t / "run"));
  EXPECT_EQ(read_file(t / "run/summary.json"), "{}");
  EXPECT_TRUE(staging_left(t.path()).empty());
}

TEST(OutputDir, AUsersNonEmptyFolderIsRefusedAndKeptEvenWithOverwrite) {
  TempDir t("safe");
  write(t / "mine/thesis.tex", "precious");
  for (bool overwrite : {false, true}) {
    EXPECT_THROW(OutputDir(t / "mine", overwrite, "run"), std::runtime_error) << overwrite;
    EXPECT_EQ(read_file(t / "mine/thesis.tex"), "precious");
  }
  EXPECT_TRUE(staging_left(t.path()).empty());
}

TEST(OutputDir, AnEarlierRownavOutputIsReplacedOnlyWithOverwrite) {
  TempDir t("safe");
  {
    OutputDir first(t / "run", false, "run");
    write(first.staging() / "old.txt", "1");
    first.commit();
  }
  EXPECT_THROW(OutputDir(t / "run", false, "run"), std::runtime_error);
  EXPECT_TRUE(fs::exists(t / "run/old.txt"));
  OutputDir second(t / "run", true, "run");
  write(second.staging() / "new.txt", "2");
  EXPECT_TRUE(fs::exists(t / "run/old.txt"));  // still there until the new one is complete
  second.commit();
  EXPECT_FALSE(fs::exists(t / "run/old.txt"));
  EXPECT_EQ(read_file(t / "run/new.txt"), "2");
  EXPECT_TRUE(staging_left(t.path()).empty());
}

TEST(OutputDir, AnEmptyFolderIsUsed) {
  TempDir t("safe");
  fs::create_directories(t / "empty");
  OutputDir out(t / "empty/", false, "run");  // trailing separator as a shell completes it
  out.commit();
  EXPECT_TRUE(is_rownav_output(t / "empty"));
}

TEST(OutputDir, TheCurrentFolderAndItsParentsAreNeverOutputs) {
  TempDir t("safe");
  write(t / "keep.txt", "x");
  fs::create_directories(t / "sub");
  const fs::path cwd = fs::current_path();
  fs::current_path(t / "sub");
  EXPECT_THROW(OutputDir(".", true, "run"), std::runtime_error);
  EXPECT_THROW(OutputDir("..", true, "run"), std::runtime_error);
  EXPECT_THROW(OutputDir("./", true, "run"), std::runtime_error);
  fs::current_path(cwd);
  EXPECT_EQ(read_file(t / "keep.txt"), "x");
  EXPECT_TRUE(fs::exists(t / "sub"));
}

TEST(OutputDir, AUsersPartialFolderBesideTheTargetIsNotTouched) {
  TempDir t("safe");
  write(t / "rec.partial/notes.txt", "mine");
  {
    OutputDir out(t / "rec", false, "recording");
    out.commit();
  }
  EXPECT_EQ(read_file(t / "rec.partial/notes.txt"), "mine");
}

TEST(OutputDir, DestroyedWithoutCommitItLeavesNothing) {
  TempDir t("safe");
  {
    OutputDir out(t / "run", false, "run");
    write(out.staging() / "lidar/000000.pcd", "half");
  }
  EXPECT_FALSE(fs::exists(t / "run"));
  EXPECT_TRUE(staging_left(t.path()).empty());
}

TEST(OutputDir, AFileOrALinkAtTheTargetIsRefused) {
  TempDir t("safe");
  write(t / "file", "x");
  fs::create_directories(t / "real");
  write(t / "real" / std::string(kOutputMarker), "rownav");
  fs::create_directory_symlink(t / "real", t / "link");
  EXPECT_THROW(OutputDir(t / "file", true, "run"), std::runtime_error);
  EXPECT_THROW(OutputDir(t / "link", true, "run"), std::runtime_error);
  EXPECT_EQ(read_file(t / "file"), "x");
}

TEST(OutputFile, AnExistingFileIsReplacedOnlyWithOverwrite) {
  TempDir t("safe");
  write(t / "rows.json", "user");
  EXPECT_THROW(OutputFile(t / "rows.json", false), std::runtime_error);
  EXPECT_EQ(read_file(t / "rows.json"), "user");
  OutputFile f(t / "rows.json", true);
  EXPECT_EQ(f.staging().extension(), ".json");  // writers pick the format by the extension
  write(f.staging(), "new");
  f.commit();
  EXPECT_EQ(read_file(t / "rows.json"), "new");
  EXPECT_TRUE(staging_left(t.path()).empty());
}

TEST(OutputFile, AUsersPartialFileIsNotTouchedAndNothingIsLeftOnError) {
  TempDir t("safe");
  write(t / "v.json.partial", "mine");
  { OutputFile f(t / "v.json", false); }
  EXPECT_EQ(read_file(t / "v.json.partial"), "mine");
  EXPECT_FALSE(fs::exists(t / "v.json"));
  EXPECT_TRUE(staging_left(t.path()).empty());
}

/// A child process makes a staging directory and a staging file, then receives `sig`.
void expect_signal_cleans_up(int sig) {
  TempDir t("safe");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    OutputDir dir(t / "run", false, "run");
    write(dir.staging() / "lidar/000001.pcd", "half");
    OutputFile file(t / "rows.json", false);
    write(file.staging(), "half");
    ::raise(sig);
    ::_exit(0);  // not reached: the signal ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the signal must still end the process";
  EXPECT_EQ(WTERMSIG(status), sig);
  EXPECT_TRUE(staging_left(t.path()).empty());
  EXPECT_FALSE(fs::exists(t / "run"));
  EXPECT_FALSE(fs::exists(t / "rows.json"));
}

TEST(OutputSignals, SigintLeavesNoStagingBehind) { expect_signal_cleans_up(SIGINT); }
TEST(OutputSignals, SigtermLeavesNoStagingBehind) { expect_signal_cleans_up(SIGTERM); }

}  // namespace
}  // namespace rownav::io
