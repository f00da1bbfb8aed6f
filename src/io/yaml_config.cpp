#include "rownav/io/yaml_config.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "rownav/io/csv.hpp"

namespace rownav::io {
namespace detail {
namespace {

/// Splits "a.b[2].c" into "a", "b", "[2]", "c".
std::vector<std::string> split_path(std::string_view path) {
  std::vector<std::string> out;
  std::string cur;
  for (const char c : path) {
    if (c == '.' || c == '[') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
      if (c == '[') cur.push_back('[');
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

/// Position of the deepest key / element named by `path`, empty unless the whole path exists.
std::string find_position(const YAML::Node& root, std::string_view path) {
  YAML::Node n = root;
  std::string pos;
  for (const auto& part : split_path(path)) {
    if (!n) return "";
    if (part.front() == '[') {
      std::size_t i = 0;
      if (!n.IsSequence() ||
          std::from_chars(part.data() + 1, part.data() + part.size(), i).ec != std::errc() ||
          i >= n.size())
        return "";
      n = n[i];
      pos = yaml_position(n);
      continue;
    }
    if (!n.IsMap()) return "";
    YAML::Node next;
    for (const auto& kv : n)
      if (kv.first.Scalar() == part) {
        pos = yaml_position(kv.first);
        next = kv.second;
      }
    if (!next) return "";
    n = next;
  }
  return pos;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

}  // namespace

std::string yaml_position(const YAML::Node& node) {
  if (!node) return "";
  const YAML::Mark m = node.Mark();
  if (m.is_null() || m.line < 0) return "";
  return std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

void yaml_fail(const std::string& file, const YAML::Node& node, const std::string& path,
               const std::string& reason) {
  throw InputError(file, yaml_position(node),
                   one_line(path.empty() ? reason : path + ": " + reason));
}

std::string yaml_describe(const YAML::Node& node) {
  if (!node || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return quote_for_message(node.Scalar());
}

bool yaml_scalar_double(const std::string& s, double& out) {
  if (s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf") {
    out = std::numeric_limits<double>::infinity();
    return true;
  }
  if (s == "-.inf" || s == "-.Inf" || s == "-.INF") {
    out = -std::numeric_limits<double>::infinity();
    return true;
  }
  if (s == ".nan" || s == ".NaN" || s == ".NAN") {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  return parse_double(s, out);
}

bool yaml_scalar_bool(const std::string& s, bool& out) {
  // Only the YAML 1.2 spellings: "yes" / "on" are too easily a typo for a string.
  if (s == "true" || s == "True" || s == "TRUE")
    out = true;
  else if (s == "false" || s == "False" || s == "FALSE")
    out = false;
  else
    return false;
  return true;
}

std::string yaml_format_double(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  return format_double(v);
}

void yaml_fail_validation(const std::string& file, const YAML::Node& root,
                          const std::string& prefix, const std::string& message) {
  const auto colon = message.find(": ");
  const std::string path = colon == std::string::npos ? "" : message.substr(0, colon);
  const std::string pos = path.empty() ? "" : find_position(root, path);
  throw InputError(file, pos, one_line(prefix.empty() ? message : prefix + "." + message));
}

void yaml_check_keys(const std::string& file, const YAML::Node& node, const std::string& path,
                     const std::vector<std::string>& valid,
                     const std::vector<std::string>& ignore) {
  std::vector<std::string> seen;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar())
      yaml_fail(file, kv.first, path, "keys must be names, got " + yaml_describe(kv.first));
    const std::string& key = kv.first.Scalar();
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      yaml_fail(file, kv.first, join_path(path, key), "duplicate key");
    seen.push_back(key);
    if (std::find(ignore.begin(), ignore.end(), key) != ignore.end()) continue;
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    std::string list;
    for (const auto& v : valid) {
      if (!list.empty()) list += ", ";
      list += v;
    }
    throw InputError(
        file, yaml_position(kv.first),
        one_line("unknown key " + quote_for_message(key) +
                 (path.empty() ? "" : " in '" + path + "'") + " (valid: " + list + ")"));
  }
}

}  // namespace detail

YAML::Node load_yaml_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw InputError(name, "", "is a directory");
  std::ifstream in(file);
  if (!in) throw InputError(name, "", std::string("cannot open: ") + std::strerror(errno));
  try {
    return YAML::Load(in);
  } catch (const YAML::Exception& e) {
    const std::string pos = e.mark.is_null() ? ""
                                             : std::to_string(e.mark.line + 1) + ":" +
                                                   std::to_string(e.mark.column + 1);
    throw InputError(name, pos, detail::one_line("invalid YAML: " + e.msg));
  }
}

void save_yaml(const std::filesystem::path& file, const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter << node;
  std::ofstream out(file);
  out << emitter.c_str() << '\n';
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

}  // namespace rownav::io
