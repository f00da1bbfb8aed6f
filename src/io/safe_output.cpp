// Outputs that never destroy what rownav did not write (io/safe_output.hpp).
#include "rownav/io/safe_output.hpp"

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rownav/core/version.hpp"

namespace rownav::io {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const fs::path& p, const std::string& why) {
  throw std::runtime_error(p.string() + ": " + why);
}

/// "out/" -> "out", "a/./b" -> "a/b"; the path a user named, without a trailing separator.
fs::path normalized(const fs::path& p) {
  fs::path n = p.lexically_normal();
  if (!n.has_filename() && n.has_parent_path()) n = n.parent_path();
  return n;
}

fs::path parent_of(const fs::path& p) {
  return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

/// ".<name>.rownav-": the start of every staging name beside `target`.
std::string staging_prefix(const fs::path& target) {
  std::string name(1, '.');  // appended piece by piece: GCC 12 warns on "." + string (-Wrestrict)
  name.append(target.filename().string()).append(".rownav-");
  return name;
}

/// A unique hidden name beside `target` (".<name>.rownav-<tag>-XXXXXX", a file keeps the
/// target's extension so writers that pick the format by it still do): mkdtemp / mkstemps.
fs::path unique_beside(const fs::path& target, const std::string& tag, bool dir) {
  const fs::path parent = parent_of(target);
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) refuse(parent, "cannot create: " + ec.message());
  const std::string ext = dir ? "" : target.extension().string();
  std::string name = staging_prefix(target);
  name.append(tag).append("-XXXXXX").append(ext);
  const std::string tmpl = (parent / name).string();
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  if (dir) {
    if (::mkdtemp(buf.data()) == nullptr) refuse(parent, "cannot create a staging directory");
  } else {
    const int fd = ::mkstemps(buf.data(), static_cast<int>(ext.size()));
    if (fd < 0) refuse(parent, "cannot create a staging file");
    ::close(fd);
  }
  // mkdtemp / mkstemps create owner-only entries; an output gets the permissions the user's
  // umask gives any new file.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  const auto all = dir ? fs::perms::all : fs::perms(0666);
  fs::permissions(buf.data(), all & ~fs::perms(mask), ec);
  return fs::path(buf.data());
}

/// True when `dir` is the current directory or one of its ancestors.
bool contains_cwd(const fs::path& dir) {
  std::error_code ec;
  const fs::path d = fs::weakly_canonical(dir, ec);
  if (ec) return false;
  const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
  if (ec) return false;
  auto c = cwd.begin();
  for (auto it = d.begin(); it != d.end(); ++it, ++c)
    if (c == cwd.end() || *it != *c) return false;
  return true;
}

}  // namespace

void remove_stale_staging(const fs::path& target) {
  const fs::path t = normalized(target);
  const std::string prefix = staging_prefix(t);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(parent_of(t), ec))
    if (e.path().filename().string().rfind(prefix, 0) == 0) fs::remove_all(e.path(), ec);
}

bool is_rownav_output(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir, ec) && fs::is_regular_file(dir / kOutputMarker, ec);
}

void check_output_dir(const fs::path& target, bool overwrite) {
  const fs::path t = normalized(target);
  std::error_code ec;
  if (t.empty()) refuse(target, "empty output path");
  if (contains_cwd(t))
    refuse(t, "is the current directory or contains it: choose a new folder for the output");
  const auto st = fs::symlink_status(t, ec);
  if (!fs::exists(st)) return;
  if (fs::is_symlink(st)) refuse(t, "is a symbolic link: choose a new folder for the output");
  if (!fs::is_directory(st)) refuse(t, "exists and is not a directory");
  if (fs::is_empty(t, ec)) return;
  if (!overwrite) refuse(t, "exists and is not empty (choose a new folder, or --overwrite to replace "
                            "an earlier rownav output)");
  if (!is_rownav_output(t))
    refuse(t, "exists and was not written by rownav (no " + std::string(kOutputMarker) +
                  " marker): refusing to replace it, even with --overwrite");
}

OutputDir::OutputDir(fs::path target, bool overwrite, std::string what)
    : target_(normalized(target)), overwrite_(overwrite), what_(std::move(what)) {
  check_output_dir(target_, overwrite_);
  staging_ = unique_beside(target_, "partial", true);
  detail::register_staging(staging_);
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);  // ours: created by mkdtemp above
  detail::unregister_staging(staging_);
}

void OutputDir::commit() {
  {
    std::ofstream m(staging_ / kOutputMarker);
    m << "rownav " << core::version() << " " << what_ << "\n";
    if (!m) refuse(staging_ / kOutputMarker, "cannot write");
  }
  check_output_dir(target_, overwrite_);  // again: the folder may have changed meanwhile
  std::error_code ec;
  std::optional<fs::path> old;
  if (fs::exists(target_, ec)) {
    if (fs::is_empty(target_, ec)) {
      fs::remove(target_, ec);  // an empty directory: nothing of the user's is lost
    } else {
      old = unique_beside(target_, "old", true);
      fs::rename(target_, *old, ec);  // replaces the empty directory just made
      if (ec) refuse(target_, "cannot move the earlier output aside: " + ec.message());
    }
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    std::error_code ignored;
    if (old) fs::rename(*old, target_, ignored);
    refuse(target_, "cannot move " + staging_.string() + " into place: " + ec.message());
  }
  committed_ = true;
  detail::unregister_staging(staging_);
  if (old) fs::remove_all(*old, ec);  // the earlier rownav output (its marker was checked)
}

OutputFile::OutputFile(fs::path target, bool overwrite) : target_(normalized(target)) {
  std::error_code ec;
  const auto st = fs::symlink_status(target_, ec);
  if (fs::exists(st) && !fs::is_regular_file(st)) refuse(target_, "exists and is not a file");
  if (fs::exists(st) && !overwrite)
    refuse(target_, "exists (choose another name, or --overwrite to replace it)");
  staging_ = unique_beside(target_, "partial", false);
  detail::register_staging(staging_);
}

OutputFile::~OutputFile() {
  if (committed_) return;
  std::error_code ec;
  fs::remove(staging_, ec);
  detail::unregister_staging(staging_);
}

void OutputFile::commit() {
  std::error_code ec;
  fs::rename(staging_, target_, ec);
  if (ec) refuse(target_, "cannot move " + staging_.string() + " into place: " + ec.message());
  committed_ = true;
  detail::unregister_staging(staging_);
}

}  // namespace rownav::io
