// End to end: every reproducer of ../shared/reliability (crashes and hangs found by hand-made
// bad inputs and a mutation fuzz, issue 13) ends quickly in one error line, exit status 2,
// without a signal and without leaving output behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"

namespace rownav {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::TempDir;

const fs::path kReliability = fs::path(ROWNAV_SHARED_DATA "/../reliability");

/// Cases that still fail, each with the reason. A case listed here is still run: the test
/// reports it, and fails once it passes (so the list cannot go stale).
const std::map<std::string, std::string> kKnownFailures = {};

struct Case {
  std::string name;
  std::string args;  // the command line without "rownav" and without a trailing "# comment"
  std::string out;   // the --out argument
};

Case load_case(const fs::path& cmd) {
  std::istringstream in(read_file(cmd));
  std::string line;
  std::getline(in, line);
  Case c{cmd.stem().string(), "", ""};
  if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
  std::istringstream words(line);
  std::vector<std::string> w;
  for (std::string s; words >> s;) w.push_back(s);
  if (w.empty() || w[0] != "rownav") return c;
  for (std::size_t i = 1; i < w.size(); ++i) {
    c.args += " " + w[i];
    if (w[i] == "--out" && i + 1 < w.size()) c.out = w[i + 1];
  }
  return c;
}

struct Outcome {
  int code = -1;  // exit status; 124 = killed by the timeout, 128 + N = signal N
  std::string err;
};

/// Runs one case with `dir` as working directory, core dumps off, killed after 20 s.
Outcome run(const fs::path& dir, const Case& c) {
  const std::string cmd = "cd '" + dir.string() + "' && ulimit -c 0 && timeout -k 5 20 '" +
                          std::string(ROWNAV_BINARY) + "'" + c.args +
                          " > .stdout 2> .stderr < /dev/null";
  const int status = std::system(cmd.c_str());
  Outcome o;
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  o.err = read_file(dir / ".stderr");
  fs::remove(dir / ".stdout");
  fs::remove(dir / ".stderr");
  return o;
}

/// Every file or folder a case left in its working directory (the config link aside).
std::vector<std::string> left_behind(const fs::path& dir) {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->path().filename() == "config" && it.depth() == 0) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_directory()) out.push_back(fs::relative(it->path(), dir).string());
  }
  return out;
}

/// Copies a read-only tree into a writable one (fs::copy would copy the folders' read-only
/// permissions, and the temporary folder could not be removed).
void copy_tree(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const auto& e : fs::recursive_directory_iterator(from)) {
    const fs::path target = to / fs::relative(e.path(), from);
    if (e.is_directory()) {
      fs::create_directories(target);
    } else {
      fs::copy_file(e.path(), target);
      fs::permissions(target, fs::perms::owner_write, fs::perm_options::add);
    }
  }
}

/// What is wrong with an outcome; empty when the case ends as it should.
std::string problems(const Case& c, const Outcome& o, const fs::path& dir) {
  std::string p;
  if (o.code != 2) p += " exit status " + std::to_string(o.code) + " (want 2);";
  const bool one_line =
      !o.err.empty() && o.err.back() == '\n' && std::count(o.err.begin(), o.err.end(), '\n') == 1;
  if (!one_line || o.err.rfind("rownav: error: ", 0) != 0)
    p += " stderr is not one 'rownav: error: ' line;";
  // The error names the offending file: every input of a case lies in ../shared/reliability.
  if (o.err.find("../shared/reliability/") == std::string::npos) p += " no file named;";
  if (!c.out.empty() && fs::exists(fs::symlink_status(dir / c.out)))
    p += " output " + c.out + " left;";
  for (const auto& f : left_behind(dir)) p += " left " + f + ";";
  return p;
}

TEST(ReliabilityCases, EveryReproducerEndsInOneErrorLine) {
  ASSERT_TRUE(fs::is_directory(kReliability / "cases")) << kReliability;
  // The commands name their inputs as ../shared/reliability/...: a scratch copy keeps that
  // layout (shared/ is read-only), each case runs in its own folder beside it.
  TempDir t("reliability");
  for (const char* part : {"cases", "seed"})
    copy_tree(kReliability / part, t / ("shared/reliability/" + std::string(part)));
  std::vector<fs::path> cmds;
  for (const auto& e : fs::directory_iterator(t / "shared/reliability/cases"))
    if (e.path().extension() == ".cmd") cmds.push_back(e.path());
  std::sort(cmds.begin(), cmds.end());
  EXPECT_GE(cmds.size(), 45u);
  int failed = 0, known = 0;
  for (const auto& cmd : cmds) {
    const Case c = load_case(cmd);
    ASSERT_FALSE(c.args.empty()) << cmd << ": not a rownav command line";
    const fs::path dir = t / ("run_" + c.name);
    fs::create_directories(dir);
    fs::create_directory_symlink(ROWNAV_SOURCE_DIR "/config", dir / "config");
    const Outcome o = run(dir, c);
    const std::string p = problems(c, o, dir);
    if (const auto k = kKnownFailures.find(c.name); k != kKnownFailures.end()) {
      ++known;
      EXPECT_FALSE(p.empty()) << c.name << " passes now: remove it from kKnownFailures";
      if (!p.empty()) std::cout << "known failure " << c.name << ": " << k->second << "\n";
      continue;
    }
    failed += !p.empty();
    EXPECT_TRUE(p.empty()) << c.name << ":" << p << "\n  rownav" << c.args
                           << "\n  stderr: " << o.err;
  }
  std::cout << cmds.size() << " cases, " << failed << " failed, " << known << " known failures\n";
}

}  // namespace
}  // namespace rownav
