#pragma once
/// @file fuzz_common.hpp What every fuzz target shares: the bytes written to a file with the
/// reader's extension (readers take paths, not buffers), and the contract of a rejected input.
///
/// The expected outcome of a bad input is io::InputError, std::invalid_argument or
/// std::runtime_error whose what() is ONE line naming the file (README: "Errors are one line").
/// Anything else is a finding: another exception type escapes to libFuzzer's abort, a message
/// with '\n' or without the file name abort()s here.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>

namespace rownav::fuzz {

namespace fs = std::filesystem;

/// A private scratch directory per process, removed at exit (fuzzers run in parallel; a crash
/// leaves it behind in $TMPDIR, which is harmless).
class ScratchDir {
 public:
  ScratchDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/rownav-fuzz-XXXXXX";
    if (!mkdtemp(templ.data())) {
      std::perror("rownav fuzz: mkdtemp");
      std::abort();
    }
    path_ = templ;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

inline const fs::path& scratch() {
  static const ScratchDir dir;
  return dir.path();
}

/// Writes `size` bytes to `file`, creating its parent directories.
inline void write_bytes(const fs::path& file, const std::uint8_t* data, std::size_t size) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) {
    std::fprintf(stderr, "rownav fuzz: cannot write %s\n", file.c_str());
    std::abort();
  }
}

/// Writes the bytes to `<scratch>/input.<ext>` and returns that path.
inline fs::path input_file(std::string_view ext, const std::uint8_t* data, std::size_t size) {
  fs::path file = scratch() / ("input." + std::string(ext));
  write_bytes(file, data, size);
  return file;
}

/// The project's promise on a rejected input: one line, naming `name` (the path given to the
/// reader, or a directory that holds every file the reader opens).
inline void check_message(const std::exception& e, const std::string& name) {
  const std::string_view what = e.what();
  const bool one_line = what.find('\n') == std::string_view::npos &&
                        what.find('\r') == std::string_view::npos && !what.empty();
  if (!one_line || what.find(name) == std::string_view::npos) {
    std::fprintf(stderr,
                 "rownav fuzz: error message breaks the one-line contract (%s, naming "
                 "%s): [%s]\n",
                 one_line ? "one line" : "NOT one line", name.c_str(), e.what());
    std::abort();
  }
}

/// Runs `read` and checks how it fails: the expected exception types with a conforming message
/// are fine; any other exception type aborts (a finding), as does a crash inside `read`.
template <class F>
void expect_clean(const std::string& name, F&& read) {
  try {
    read();
  } catch (const std::invalid_argument& e) {
    check_message(e, name);
  } catch (const std::runtime_error& e) {  // io::InputError derives from it
    check_message(e, name);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rownav fuzz: unexpected exception type (%s): %s\n", typeid(e).name(),
                 e.what());
    std::abort();
  }
}

}  // namespace rownav::fuzz
