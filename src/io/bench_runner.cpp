// Parallel, resumable execution of benchmark cells as child processes.
#include "rownav/io/bench_runner.hpp"

#include "rownav/io/safe_output.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace rownav::io {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t g_stop = 0;

/// The bench folder must be new, empty or an earlier bench output (resumed): never a user's.
void claim_bench_dir(const fs::path& out) {
  check_output_dir(out, true);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw std::runtime_error(out.string() + ": cannot create: " + ec.message());
  if (is_rownav_output(out)) return;
  std::ofstream(out / kOutputMarker) << "rownav bench\n";
  if (!is_rownav_output(out)) throw std::runtime_error(out.string() + ": cannot write");
}

extern "C" void on_stop_signal(int) {
  g_stop = 1;
}

// Installs the SIGINT / SIGTERM handlers for its lifetime.
class StopSignals {
 public:
  StopSignals() {
    g_stop = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

// Starts `runner run args...` with stdout / stderr appended to `log` (which first gets the
// command line); -1 and errno-like code in `error` when it cannot be started.
pid_t spawn(const fs::path& runner, const std::vector<std::string>& args, const fs::path& log,
            int& error) {
  std::vector<std::string> words = {runner.string(), "run"};
  words.insert(words.end(), args.begin(), args.end());
  {
    std::ofstream f(log, std::ios::trunc);
    f << "$";
    for (const auto& w : words) f << " '" << w << "'";
    f << "\n";
  }
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_APPEND, 0);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setpgroup(&attr, 0);  // its own group: a stop terminates its children too
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);
  pid_t pid = -1;
  error = posix_spawn(&pid, runner.c_str(), &fa, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  return error == 0 ? pid : -1;
}

std::string clock_text(double seconds) {
  if (!(seconds >= 0) || seconds > 1e7) return "--:--";
  const long long s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  return buf;
}

std::string exit_text(int status) {
  if (WIFEXITED(status)) return "exit " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "stopped";
}

struct Running {
  pid_t pid;
  std::size_t index;
  Clock::time_point start;
};

// The run loop's state and its progress lines.
class Batch {
 public:
  Batch(const std::vector<BenchCell>& cells, const fs::path& out, const BenchRunnerOptions& o)
      : cells_(cells), out_(out), o_(o), start_(Clock::now()) {
    result_.cells.resize(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) result_.cells[i].id = cells[i].id;
  }

  BenchRunResult run() {
    const StopSignals signals;
    std::size_t next = 0;
    while (true) {
      while (!g_stop && running_.size() < static_cast<std::size_t>(o_.jobs) && next < cells_.size())
        launch(next++);
      if (g_stop || (running_.empty() && next >= cells_.size())) break;
      reap();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (g_stop) stop_all();
    result_.interrupted = g_stop != 0;
    return std::move(result_);
  }

 private:
  void launch(std::size_t i) {
    const fs::path dir = cell_dir(out_, cells_[i]);
    if (fs::is_regular_file(dir / "summary.json")) {
      finish(i, CellStatus::resumed, "resumed: summary.json exists, not run again");
      return;
    }
    // A fresh start: no half-written output of an earlier, killed attempt (the bench folder is
    // rownav's, claimed by run_cells; a runner killed with SIGKILL may leave its staging folder).
    fs::remove_all(dir);
    remove_stale_staging(dir);
    fs::create_directories(dir.parent_path());
    int error = 0;
    const pid_t pid = spawn(o_.runner, cells_[i].run_args(dir), running_log(i), error);
    if (pid < 0) {
      store_log(i);
      finish(i, CellStatus::failed, std::string("cannot start runner: ") + std::strerror(error));
      return;
    }
    running_.push_back({pid, i, Clock::now()});
  }

  void reap() {
    for (auto it = running_.begin(); it != running_.end();) {
      int status = 0;
      if (::waitpid(it->pid, &status, WNOHANG) != it->pid) {
        ++it;
        continue;
      }
      const double secs = std::chrono::duration<double>(Clock::now() - it->start).count();
      char took[32];
      std::snprintf(took, sizeof took, " in %.1f s", secs);
      const fs::path dir = cell_dir(out_, cells_[it->index]);
      store_log(it->index);
      if (fs::is_regular_file(dir / "summary.json"))
        finish(it->index, CellStatus::ran, "done (" + exit_text(status) + ")" + took);
      else
        finish(it->index, CellStatus::failed,
               "FAILED (" + exit_text(status) + ", no summary.json), see " +
                   (dir / "log.txt").string());
      it = running_.erase(it);
    }
  }

  // Terminates the running children (SIGTERM, SIGKILL after 5 s) and waits for them.
  void stop_all() {
    for (const auto& r : running_) ::kill(-r.pid, SIGTERM);
    const auto deadline = Clock::now() + std::chrono::seconds(5);
    for (const auto& r : running_) {
      int status = 0;
      while (::waitpid(r.pid, &status, WNOHANG) == 0) {
        if (Clock::now() > deadline) {
          ::kill(-r.pid, SIGKILL);
          ::waitpid(r.pid, &status, 0);
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      store_log(r.index);
      result_.cells[r.index].detail = "interrupted";
    }
    if (o_.progress)
      *o_.progress << "bench: interrupted: " << running_.size()
                   << " running cell(s) terminated; run again to resume\n";
    running_.clear();
  }

  // The log is written next to the cell's folder while it runs (the runner may create or
  // rename the folder itself), then moved into it.
  fs::path running_log(std::size_t i) const {
    return cell_dir(out_, cells_[i]).string() + ".log.txt";
  }
  void store_log(std::size_t i) const {
    const fs::path dir = cell_dir(out_, cells_[i]);
    std::error_code ec;
    fs::create_directories(dir, ec);
    fs::rename(running_log(i), dir / "log.txt", ec);
  }

  void finish(std::size_t i, CellStatus s, const std::string& detail) {
    result_.cells[i].status = s;
    result_.cells[i].detail = detail;
    ++done_;
    if (s != CellStatus::resumed) ++executed_;
    if (!o_.progress) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double eta = executed_ > 0 ? elapsed / executed_ * double(cells_.size() - done_) : -1;
    *o_.progress << "bench [" << done_ << "/" << cells_.size() << ", "
                 << result_.count(CellStatus::failed) << " failed, ETA " << clock_text(eta) << "] "
                 << cells_[i].id << ": " << detail << "\n"
                 << std::flush;
  }

  const std::vector<BenchCell>& cells_;
  fs::path out_;
  const BenchRunnerOptions& o_;
  Clock::time_point start_;
  std::vector<Running> running_;
  BenchRunResult result_;
  std::size_t done_ = 0, executed_ = 0;
};

}  // namespace

int BenchRunResult::count(CellStatus s) const {
  return static_cast<int>(
      std::count_if(cells.begin(), cells.end(), [s](const auto& c) { return c.status == s; }));
}

BenchRunResult run_cells(const std::vector<BenchCell>& cells, const fs::path& out,
                         const BenchRunnerOptions& options) {
  if (::access(options.runner.c_str(), X_OK) != 0)
    throw std::runtime_error(options.runner.string() + ": runner is not an executable file");
  if (options.jobs < 1) throw std::invalid_argument("--jobs: must be >= 1");
  claim_bench_dir(out);
  return Batch(cells, out, options).run();
}

}  // namespace rownav::io
