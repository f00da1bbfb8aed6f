#include "rownav/io/csv.hpp"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

template <class T>
bool parse_floating(std::string_view s, T& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

template <class T>
std::string format_floating(T v) {
  std::array<char, 64> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  (void)ec;  // 64 characters always suffice for the shortest representation
  return std::string(buf.data(), end);
}

}  // namespace

std::string format_double(double v) {
  return format_floating(v);
}
std::string format_float(float v) {
  return format_floating(v);
}
bool parse_double(std::string_view s, double& out) {
  return parse_floating(s, out);
}
bool parse_float(std::string_view s, float& out) {
  return parse_floating(s, out);
}

bool parse_int64(std::string_view s, std::int64_t& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

std::string quote_for_message(std::string_view s) {
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < 40; ++i) {
    const char c = s[i];
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (static_cast<unsigned char>(c) < 0x20)
      out += '?';
    else
      out += c;
  }
  if (s.size() > 40) out += "...";
  return out + "'";
}

CsvReader::CsvReader(const std::filesystem::path& file) : file_(file.string()) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw InputError(file_, "", "is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file_, "", std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  text_ = ss.str();
  if (text_.rfind("\xEF\xBB\xBF", 0) == 0) pos_ = 3;  // UTF-8 byte-order mark (spreadsheet exports)
}

bool CsvReader::next() {
  while (pos_ < text_.size()) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    const std::string_view line = trim(std::string_view(text_).substr(pos_, end - pos_));
    pos_ = end + 1;
    ++line_;
    if (line.empty() || line.front() == '#') continue;
    cells_.clear();
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      cells_.push_back(
          trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return true;
  }
  return false;
}

double CsvReader::number(std::size_t i, std::string_view column) const {
  double v = 0.0;
  if (i >= cells_.size() || !parse_double(cells_[i], v))
    fail("expected a number in column '" + std::string(column) + "', got " +
         quote_for_message(i < cells_.size() ? cells_[i] : std::string_view()));
  return v;
}

float CsvReader::number_f(std::size_t i, std::string_view column) const {
  float v = 0.0f;
  if (i >= cells_.size() || !parse_float(cells_[i], v))
    fail("expected a number in column '" + std::string(column) + "', got " +
         quote_for_message(i < cells_.size() ? cells_[i] : std::string_view()));
  return v;
}

std::int64_t CsvReader::integer(std::size_t i, std::string_view column) const {
  std::int64_t v = 0;
  if (i >= cells_.size() || !parse_int64(cells_[i], v))
    fail("expected an integer in column '" + std::string(column) + "', got " +
         quote_for_message(i < cells_.size() ? cells_[i] : std::string_view()));
  return v;
}

void CsvReader::expect_size(std::size_t n) const {
  if (cells_.size() != n)
    fail("expected " + std::to_string(n) + " columns, got " + std::to_string(cells_.size()));
}

void CsvReader::expect_header(const std::vector<std::string_view>& names) const {
  bool ok = names.size() == cells_.size();
  for (std::size_t i = 0; ok && i < names.size(); ++i) ok = names[i] == cells_[i];
  if (ok) return;
  std::string want;
  for (const auto n : names) {
    if (!want.empty()) want += ',';
    want += n;
  }
  fail("expected header '" + want + "'");
}

void CsvReader::fail(const std::string& reason) const {
  throw InputError(file_, std::to_string(line_), reason);
}

}  // namespace rownav::io
