#include "cloud_header_check.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "rownav/io/csv.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io::detail {
namespace {

/// LZF (PCD binary_compressed) codes at most 264 bytes in one 3-byte back reference.
constexpr std::uint64_t kMaxLzfRatio = 88;

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::string line_position(int line) {
  return line > 0 ? "line " + std::to_string(line) : "";
}

/// a * b <= cap without overflow (a, b >= 0).
bool product_fits(std::uint64_t a, std::uint64_t b, std::uint64_t cap) {
  return a == 0 || b <= cap / a;
}

bool parse_rownav_comment(const std::string& line, core::PointCloud& out) {
  const auto stamp = line.find("stamp="), flags = line.find(" flags="),
             frame = line.find(" frame_id=");
  if (stamp == std::string::npos || flags == std::string::npos || frame == std::string::npos ||
      flags < stamp || frame < flags)
    return false;
  parse_double(std::string_view(line).substr(stamp + 6, flags - stamp - 6), out.stamp);
  const std::string f = line.substr(flags + 7, frame - flags - 7);
  out.has_intensity = f.find('i') != std::string::npos;
  out.has_ring = f.find('r') != std::string::npos;
  out.has_time = f.find('t') != std::string::npos;
  out.frame_id = line.substr(frame + 10);
  return true;
}

// ---- PCD ----

struct PcdHeader {
  std::map<std::string, std::vector<std::string>> keys;
  std::map<std::string, int> lines;  // key -> 1-based line
  std::uint64_t data_offset = 0;     // first byte after the DATA line
};

constexpr std::array<std::string_view, 10> kPcdKeys{
    "VERSION", "FIELDS", "SIZE", "TYPE", "COUNT", "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};

[[noreturn]] void bad_pcd(const std::string& name, int line, const std::string& why) {
  throw InputError(name, line_position(line), "not a valid PCD file (" + why + ")");
}

PcdHeader read_pcd_header(std::istream& in, const std::string& name, core::PointCloud& meta,
                          bool& has_meta) {
  PcdHeader h;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    // PCL 1.13 skips only truly empty lines: one of blanks ("\t", "   ", a CRLF file's "\r")
    // reaches its keyword switch with no keyword and PCDReader::read crashes (pcd_fuzz).
    if (!line.empty() && line.find_first_not_of(" \t\r") == std::string::npos)
      bad_pcd(name, n, "a header line of blanks only");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("# rownav ", 0) == 0) has_meta = parse_rownav_comment(line, meta);
    if (line.empty() || line[0] == '#') continue;
    // PCL 1.13 splits header lines on spaces, tabs and CRs only: a line of other control bytes
    // (a vertical tab, pcd_fuzz) reaches its keyword switch empty and PCDReader::read crashes.
    if (std::any_of(line.begin(), line.end(),
                    [](unsigned char c) { return c < 0x20 && c != '\t'; }))
      bad_pcd(name, n, "control character in a header line");
    auto w = words(line);
    if (w.empty()) continue;
    const std::string key = w[0];
    if (std::find(kPcdKeys.begin(), kPcdKeys.end(), key) == kPcdKeys.end())
      bad_pcd(name, n, "unknown header keyword " + quote_for_message(key));
    if (h.keys.count(key)) bad_pcd(name, n, "duplicate " + key);
    w.erase(w.begin());
    h.keys[key] = w;
    h.lines[key] = n;
    if (key == "DATA") {
      h.data_offset = static_cast<std::uint64_t>(in.tellg());
      return h;
    }
  }
  bad_pcd(name, 0, "no DATA line");
}

/// PCL 1.13's PCDReader does not stop at DATA: it reads on while a line's first word starts
/// with a header keyword (or is a comment), and "COLUMNS" is its synonym of FIELDS. Data whose
/// first line looks like that redefines the fields after the sizes were set: a heap
/// use-after-free in PCDReader::read (pcd_fuzz, issue 13). Refuse it; real binary data starts
/// so by chance about once in 2^32 files (a first float spelling "SIZE"...).
void check_data_start(const std::filesystem::path& file, const PcdHeader& h,
                      const std::string& name) {
  static constexpr std::array<std::string_view, 11> kPclPrefixes{
      "VERSION", "FIELDS", "COLUMNS",   "SIZE",   "TYPE", "COUNT",
      "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
  std::ifstream in(file, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(h.data_offset));
  std::string line;
  // PCL takes a line's first word with `stream >> word`, which skips every isspace() byte: a
  // data line "\v# ..." is a comment to it, and the header keyword on the next line is read
  // (pcd_fuzz: FIELDS after DATA, then a 4 EB allocation).
  static constexpr const char* kBlanks = " \t\r\v\f";
  for (int n = h.lines.at("DATA") + 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(kBlanks);
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string_view word =
        std::string_view(line).substr(first, line.find_first_of(kBlanks, first) - first);
    for (const auto& k : kPclPrefixes)
      if (word.substr(0, k.size()) == k)
        bad_pcd(name, n,
                "the data starts with the header keyword " + quote_for_message(word) +
                    ", which PCL would read as header");
    return;
  }
}

/// Bytes per point and values per point; checks FIELDS / SIZE / TYPE / COUNT agree.
std::pair<std::int64_t, std::int64_t> pcd_point_layout(PcdHeader& h, const std::string& name) {
  auto& k = h.keys;
  const std::size_t nf = k["FIELDS"].size();
  if (!k.count("COUNT")) k["COUNT"] = std::vector<std::string>(nf, "1");
  if (nf == 0 || k["SIZE"].size() != nf || k["TYPE"].size() != nf || k["COUNT"].size() != nf)
    bad_pcd(name, h.lines["FIELDS"], "FIELDS, SIZE, TYPE and COUNT disagree");
  std::int64_t step = 0, values = 0;
  for (std::size_t i = 0; i < nf; ++i) {
    const std::string& sz = k["SIZE"][i];
    const std::string& ty = k["TYPE"][i];
    std::int64_t size = 0, count = 0;
    const bool ok =
        parse_int64(sz, size) && parse_int64(k["COUNT"][i], count) && count >= 1 &&
        count < 1000000 &&
        ((ty == "F" && (size == 4 || size == 8)) ||
         ((ty == "I" || ty == "U") && (size == 1 || size == 2 || size == 4 || size == 8)));
    if (!ok)
      bad_pcd(name, h.lines["SIZE"], "field " + k["FIELDS"][i] + ": TYPE " + ty + " SIZE " + sz);
    step += size * count;
    values += count;
  }
  return {step, values};
}

std::int64_t pcd_count(PcdHeader& h, const std::string& key, const std::string& name) {
  const auto& v = h.keys[key];
  std::int64_t x = -1;
  if (v.size() != 1 || !parse_int64(v[0], x) || x < 0 || x > kMaxCloudElements)
    bad_pcd(name, h.lines[key],
            key + " must be an integer in [0, " + std::to_string(kMaxCloudElements) + "]");
  return x;
}

/// The data after the header must hold `points` points of `step` bytes / `values` numbers.
void check_pcd_data(std::istream& in, const PcdHeader& h, const std::string& name,
                    std::uint64_t available, std::uint64_t points,
                    std::pair<std::int64_t, std::int64_t> layout) {
  const auto step = static_cast<std::uint64_t>(layout.first);
  const auto values = static_cast<std::uint64_t>(layout.second);
  const int line = h.lines.at("DATA");
  const auto& data = h.keys.at("DATA");
  const std::string kind = data.size() == 1 ? data[0] : "";
  if (kind == "ascii") {  // every number takes a character and a separator
    if (!product_fits(points, 2 * values, available + 1))
      bad_pcd(name, line, "POINTS " + std::to_string(points) + " do not fit the ascii data");
  } else if (kind == "binary") {
    if (!product_fits(points, step, available)) bad_pcd(name, line, "binary data truncated");
  } else if (kind == "binary_compressed") {
    if (points == 0) return;
    std::uint32_t sizes[2] = {0, 0};  // compressed, uncompressed
    if (!product_fits(points, step, std::numeric_limits<std::uint32_t>::max()) || available < 8 ||
        !in.read(reinterpret_cast<char*>(sizes), 8) || sizes[1] != points * step ||
        available < 8 + std::uint64_t{sizes[0]} ||
        std::uint64_t{sizes[1]} > kMaxLzfRatio * std::uint64_t{sizes[0]})
      bad_pcd(name, line, "compressed data truncated or inconsistent");
  } else {
    bad_pcd(name, line, "DATA must be ascii, binary or binary_compressed");
  }
}

// ---- PLY ----

[[noreturn]] void bad_ply(const std::string& name, int line, const std::string& why) {
  throw InputError(name, line_position(line), "not a valid PLY file (" + why + ")");
}

/// Bytes of a PLY scalar type, 0 when unknown.
std::uint64_t ply_type_size(const std::string& t) {
  static const std::map<std::string, std::uint64_t> sizes{
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t min_bytes = 0;  // binary: fixed properties + list counts
  std::uint64_t values = 0;     // ascii: numbers at least (a list: its count)
  int line = 0;
};

struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  std::uint64_t data_offset = 0;
};

void add_ply_property(PlyHeader& h, const std::vector<std::string>& w, const std::string& name,
                      int n) {
  if (h.elements.empty()) bad_ply(name, n, "property before any element");
  const bool list = w.size() == 5 && w[1] == "list";
  if (!list && w.size() != 3) bad_ply(name, n, "expected 'property TYPE NAME'");
  const std::uint64_t size = ply_type_size(w[1 + list]);
  const bool int_count = !list || (w[2].find("float") == std::string::npos && w[2] != "double" &&
                                   ply_type_size(w[3]) > 0);
  if (size == 0 || !int_count) bad_ply(name, n, "unknown property type");
  // A point cloud's vertex holds numbers, not lists: PCL's reader asserts on a vertex list
  // property (the PLY fuzzer found it); faces carry the lists.
  if (list && h.elements.back().name == "vertex")
    bad_ply(name, n, "list property " + quote_for_message(w[4]) + " in element 'vertex'");
  h.elements.back().min_bytes += size;
  h.elements.back().values += 1;
}

void add_ply_element(PlyHeader& h, const std::vector<std::string>& w, const std::string& name,
                     int n) {
  std::int64_t count = -1;
  if (w.size() != 3 || !parse_int64(w[2], count) || count < 0 || count > kMaxCloudElements)
    bad_ply(name, n,
            "element " + quote_for_message(w.size() > 1 ? w[1] : "") + ": count " +
                quote_for_message(w.size() > 2 ? w[2] : "") + " must be an integer in [0, " +
                std::to_string(kMaxCloudElements) + "]");
  h.elements.push_back({w[1], static_cast<std::uint64_t>(count), 0, 0, n});
}

PlyHeader read_ply_header(std::istream& in, const std::string& name) {
  PlyHeader h;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto w = words(line);
    if (n == 1) {
      if (line != "ply") bad_ply(name, n, "no 'ply' first line");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format" && w.size() == 3 &&
        (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian")) {
      h.format = w[1];
    } else if (w[0] == "element") {
      add_ply_element(h, w, name, n);
    } else if (w[0] == "property") {
      add_ply_property(h, w, name, n);
    } else if (w[0] == "end_header" && w.size() == 1) {
      if (h.format.empty()) bad_ply(name, n, "no format line");
      h.data_offset = static_cast<std::uint64_t>(in.tellg());
      return h;
    } else {
      bad_ply(name, n, "unknown header line " + quote_for_message(line));
    }
  }
  bad_ply(name, 0, "no end_header line");
}

}  // namespace

bool check_pcd_header(const std::filesystem::path& file, const std::string& name,
                      core::PointCloud& meta) {
  std::ifstream in(file, std::ios::binary);
  bool has_meta = false;
  PcdHeader h = read_pcd_header(in, name, meta, has_meta);
  for (const char* k : {"FIELDS", "SIZE", "TYPE", "WIDTH", "POINTS"})
    if (!h.keys.count(k)) bad_pcd(name, 0, std::string("no ") + k);
  const auto layout = pcd_point_layout(h, name);
  if (!h.keys.count("HEIGHT")) h.keys["HEIGHT"] = {"1"};
  const std::int64_t width = pcd_count(h, "WIDTH", name), height = pcd_count(h, "HEIGHT", name);
  const std::int64_t points = pcd_count(h, "POINTS", name);
  if (width * height != points) bad_pcd(name, h.lines["POINTS"], "WIDTH x HEIGHT != POINTS");
  const std::uint64_t size = std::filesystem::file_size(file);
  const std::uint64_t available = size > h.data_offset ? size - h.data_offset : 0;
  check_pcd_data(in, h, name, available, static_cast<std::uint64_t>(points), layout);
  check_data_start(file, h, name);
  return has_meta;
}

void check_ply_header(const std::filesystem::path& file, const std::string& name) {
  std::ifstream in(file, std::ios::binary);
  const PlyHeader h = read_ply_header(in, name);
  const std::uint64_t size = std::filesystem::file_size(file);
  const std::uint64_t available = size > h.data_offset ? size - h.data_offset : 0;
  const bool ascii = h.format == "ascii";
  // The last ascii number may end the file without a separator: one byte of slack.
  std::uint64_t left = ascii ? available + 1 : available;
  for (const auto& e : h.elements) {
    const std::uint64_t each = ascii ? 2 * e.values : e.min_bytes;
    if (!product_fits(e.count, each, left))
      bad_ply(name, e.line,
              "element " + quote_for_message(e.name) + ": " + std::to_string(e.count) +
                  " elements do not fit the " + std::to_string(available) + " bytes of data");
    left -= e.count * each;
  }
}

}  // namespace rownav::io::detail
