#pragma once
/// @file safe_output.hpp Outputs that never destroy what rownav did not write.
///
/// Rules (issue 13, "data loss"):
/// - a directory output is written into a uniquely named hidden staging directory beside the
///   target and moved into place on commit(); an existing non-empty target is replaced only with
///   `overwrite` AND when it holds the marker file `.rownav-output` that every rownav output
///   directory carries; the current directory (or one containing it) is never an output;
/// - a file output is written into a uniquely named hidden staging file beside it; an existing
///   file is replaced only with `overwrite`;
/// - staging paths are removed when the writer is destroyed without commit() (an error) and by
///   a SIGINT / SIGTERM handler (Ctrl-C, kill), which then lets the signal end the process.
/// Every refusal is a std::runtime_error with one line naming the path and the reason.
#include <filesystem>
#include <string>
#include <string_view>

namespace rownav::io {

/// Name of the marker file in every directory rownav writes.
inline constexpr std::string_view kOutputMarker = ".rownav-output";

/// True when `dir` is a directory holding the rownav marker file.
bool is_rownav_output(const std::filesystem::path& dir);

/// Throws unless `dir` may be used as a directory output: a missing path, an empty directory, or
/// (with `overwrite`) a rownav output. Called before any long computation, so a user learns of a
/// refused output at once.
void check_output_dir(const std::filesystem::path& dir, bool overwrite);

/// A directory output written into a staging directory and moved into place by commit().
class OutputDir {
 public:
  /// Checks `target` (check_output_dir) and creates the staging directory. `what` is written to
  /// the marker (e.g. "run", "recording").
  OutputDir(std::filesystem::path target, bool overwrite, std::string what);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  /// Where to write until commit().
  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& target() const { return target_; }
  /// Writes the marker and moves the staging directory to the target (an existing rownav output
  /// there is replaced). Throws std::runtime_error when the move fails (the target is kept).
  void commit();
  bool committed() const { return committed_; }

 private:
  std::filesystem::path target_, staging_;
  bool overwrite_ = false, committed_ = false;
  std::string what_;
};

/// A file output written into a staging file and renamed over the target by commit().
class OutputFile {
 public:
  /// Throws when `target` exists and is not a regular file, or exists and `overwrite` is false.
  OutputFile(std::filesystem::path target, bool overwrite);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& target() const { return target_; }
  void commit();

 private:
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

/// Removes staging paths an OutputDir / OutputFile left beside `target` (a process killed with
/// SIGKILL cannot clean up): only names of rownav's staging pattern for that target.
void remove_stale_staging(const std::filesystem::path& target);

namespace detail {
/// Registers a staging path for removal by the SIGINT / SIGTERM handler (installed on first
/// use). Returns false when every slot is taken (the path is then only removed by destructors).
bool register_staging(const std::filesystem::path& p);
void unregister_staging(const std::filesystem::path& p);
}  // namespace detail

}  // namespace rownav::io
