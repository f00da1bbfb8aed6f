// Removal of staging outputs on SIGINT / SIGTERM / SIGHUP (io/safe_output.hpp). The handler
// only uses async-signal-safe system calls (openat, getdents64, unlinkat, close), so it is safe
// whatever the interrupted thread was doing.
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <mutex>

#include "rownav/io/safe_output.hpp"

namespace rownav::io::detail {

namespace {

/// Staging paths alive at once (nested outputs: a run directory, a picture, a log).
constexpr std::size_t kSlots = 32;
/// Directory depth the handler descends (recordings are two levels deep).
constexpr int kMaxDepth = 16;

struct Slot {
  std::atomic<bool> used{false};
  char path[PATH_MAX] = {};
};

std::array<Slot, kSlots> g_slots;
std::mutex g_mutex;  // registration only; the handler never locks

struct Dirent64 {
  ino64_t d_ino;
  off64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[];
};

bool dot_or_dotdot(const char* n) {
  return n[0] == '.' && (n[1] == '\0' || (n[1] == '.' && n[2] == '\0'));
}

// Removes `name` (relative to dirfd) and, for a directory, everything below it.
void remove_tree_at(int dirfd, const char* name, int depth) {
  if (::unlinkat(dirfd, name, 0) == 0 || (errno != EISDIR && errno != EPERM)) return;
  if (depth > kMaxDepth) return;
  const int fd = ::openat(dirfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) char buf[4096];
  bool removed = true;
  while (removed) {  // entries removed while listing can hide others: list again until none
    removed = false;
    ::lseek(fd, 0, SEEK_SET);
    long n = 0;
    while ((n = ::syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0)
      for (long off = 0; off < n;) {
        const auto* d = reinterpret_cast<const Dirent64*>(buf + off);
        off += d->d_reclen;
        if (dot_or_dotdot(d->d_name)) continue;
        remove_tree_at(fd, d->d_name, depth + 1);
        removed = true;
      }
  }
  ::close(fd);
  ::unlinkat(dirfd, name, AT_REMOVEDIR);
}

extern "C" void remove_staging_on_signal(int sig) {
  const int saved = errno;
  for (auto& s : g_slots)
    if (s.used.load(std::memory_order_acquire)) remove_tree_at(AT_FDCWD, s.path, 0);
  errno = saved;
  // The signal then ends the process as it would have without us (exit status 128 + sig).
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
      struct sigaction sa {};
      sa.sa_handler = remove_staging_on_signal;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

}  // namespace

bool register_staging(const std::filesystem::path& p) {
  std::error_code ec;
  const std::string abs = std::filesystem::absolute(p, ec).string();
  if (ec || abs.size() >= PATH_MAX) return false;
  install_once();
  const std::lock_guard lock(g_mutex);
  for (auto& s : g_slots) {
    if (s.used.load(std::memory_order_relaxed)) continue;
    std::memcpy(s.path, abs.c_str(), abs.size() + 1);
    s.used.store(true, std::memory_order_release);
    return true;
  }
  return false;
}

void unregister_staging(const std::filesystem::path& p) {
  std::error_code ec;
  const std::string abs = std::filesystem::absolute(p, ec).string();
  const std::lock_guard lock(g_mutex);
  for (auto& s : g_slots)
    if (s.used.load(std::memory_order_relaxed) && abs == s.path) {
      s.used.store(false, std::memory_order_release);
      return;
    }
}

}  // namespace rownav::io::detail
