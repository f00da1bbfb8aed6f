#include "rownav/io/mesh_reader.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "rownav/io/csv.hpp"

namespace rownav::io {
namespace {

/// The file's text, or only its first `limit` bytes.
std::string file_text(const std::filesystem::path& file, std::size_t limit = std::string::npos) {
  std::ifstream in(file, std::ios::binary);
  if (limit != std::string::npos) {
    std::string head(limit, '\0');
    in.read(head.data(), static_cast<std::streamsize>(limit));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return head;
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// "line:col" (1-based) of byte `at`.
std::string text_position(std::string_view text, std::size_t at) {
  const std::string_view head = text.substr(0, at);
  const auto line = 1 + std::count(head.begin(), head.end(), '\n');
  const auto nl = head.rfind('\n');
  const std::size_t col = nl == std::string_view::npos ? at + 1 : at - nl;
  return std::to_string(line) + ":" + std::to_string(col);
}

/// Value of attribute `name` in the start tag `tag` ("<accessor a=\"1\" ...>"), if present.
std::optional<std::string> attribute(std::string_view tag, std::string_view name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    const std::size_t eq = at + name.size();
    if (at == 0 || !std::isspace(static_cast<unsigned char>(tag[at - 1])) || eq + 1 >= tag.size() ||
        tag[eq] != '=' || (tag[eq + 1] != '"' && tag[eq + 1] != '\''))
      continue;
    const std::size_t end = tag.find(tag[eq + 1], eq + 2);
    if (end == std::string_view::npos) return std::nullopt;
    return std::string(tag.substr(eq + 2, end - eq - 2));
  }
  return std::nullopt;
}

struct ColladaScan {
  std::string_view text;
  std::string name;

  [[noreturn]] void fail(std::size_t at, const std::string& why) const {
    throw InputError(name, text_position(text, at), "unreadable mesh: " + why);
  }
  /// Attribute `key` of the tag at `at` as a count (absent: `fallback`).
  std::uint64_t count(std::string_view tag, std::size_t at, std::string_view key,
                      std::uint64_t fallback) const {
    const auto v = attribute(tag, key);
    std::int64_t x = -1;
    if (!v) return fallback;
    if (!parse_int64(*v, x) || x < 0)
      fail(at, std::string(key) + " " + quote_for_message(*v) + " is not a count");
    return static_cast<std::uint64_t>(x);
  }
  /// Every `<X_array id=... count=...>`: id -> count; no array holds more values than the file
  /// has bytes.
  std::map<std::string, std::uint64_t> arrays() const {
    std::map<std::string, std::uint64_t> out;
    for (std::size_t at = text.find("_array"); at != std::string_view::npos;
         at = text.find("_array", at + 1)) {
      const std::size_t open = text.rfind('<', at), close = text.find('>', at);
      if (open == std::string_view::npos || close == std::string_view::npos ||
          text.substr(open, at - open).find_first_of(" \t\r\n/>") != std::string_view::npos)
        continue;
      const std::string_view tag = text.substr(open, close - open);
      const std::uint64_t n = count(tag, open, "count", 0);
      if (n > text.size()) fail(open, "array count " + std::to_string(n) + " exceeds the file");
      if (const auto id = attribute(tag, "id")) out[*id] = n;
    }
    return out;
  }
  /// Index lists (`<p>`, `<vcount>`, `<v>`, `<h>`) hold only unsigned integers: assimp 5's
  /// parser does not advance on another character and appends indices until memory runs out
  /// (`<p>0!1 2</p>`: 800 MB, found by mesh_fuzz, issue 13).
  void check_index_lists() const {
    for (const std::string_view tag : {"<p>", "<vcount>", "<v>", "<h>"})
      for (std::size_t at = text.find(tag); at != std::string_view::npos;
           at = text.find(tag, at + 1)) {
        const std::size_t begin = at + tag.size(), end = text.find('<', begin);
        const std::string_view list = text.substr(begin, end - begin);
        const std::size_t bad = list.find_first_not_of("0123456789 \t\r\n");
        if (bad != std::string_view::npos)
          fail(begin + bad, std::string(tag) + " holds " + quote_for_message(list.substr(bad, 1)) +
                                ", not an index");
      }
  }
  /// Every `<accessor>` must read inside its array: offset + (count - 1) * stride + params.
  void check_accessors() const {
    const auto sizes = arrays();
    for (std::size_t at = text.find("<accessor"); at != std::string_view::npos;
         at = text.find("<accessor", at + 1)) {
      const std::size_t close = text.find('>', at), end = text.find("</accessor", at);
      if (close == std::string_view::npos) fail(at, "unterminated accessor");
      const std::string_view tag = text.substr(at, close - at);
      const std::string_view body =
          text.substr(close, end == std::string_view::npos ? 0 : end - close);
      std::uint64_t params = 0;
      for (auto p = body.find("<param"); p != std::string_view::npos;
           p = body.find("<param", p + 1))
        ++params;
      const std::uint64_t n = count(tag, at, "count", 0), stride = count(tag, at, "stride", 1),
                          offset = count(tag, at, "offset", 0);
      const std::string source = attribute(tag, "source").value_or("");
      const auto it = sizes.find(source.rfind('#', 0) == 0 ? source.substr(1) : source);
      if (it == sizes.end())
        fail(at, "accessor source " + quote_for_message(source) + " not found");
      const std::uint64_t avail = it->second, last = std::max<std::uint64_t>(params, 1);
      if (n == 0) continue;
      if (offset > avail || last > avail - offset ||
          (n - 1 > 0 && stride > (avail - offset - last) / (n - 1)))
        fail(at, "accessor count " + std::to_string(n) + " x stride " + std::to_string(stride) +
                     " reads past the " + std::to_string(avail) + " values of its array");
    }
  }
};

/// By extension or content: assimp picks its importer both ways.
bool is_collada(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".dae" || file_text(file, 4096).find("<COLLADA") != std::string::npos;
}

}  // namespace

sim::TriangleMesh read_mesh(const std::filesystem::path& file, sim::SurfaceClass label) {
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) throw InputError(name, "", "no such file");
  // assimp 5's Collada importer trusts accessor counts and strides (a huge stride reads far
  // outside the array and crashes): check them against the arrays first.
  if (is_collada(file)) {
    const std::string text = file_text(file);
    const ColladaScan scan{text, name};
    scan.check_index_lists();
    scan.check_accessors();
  }
  Assimp::Importer importer;
  // Pre-transforming bakes the node hierarchy (DAE / OBJ groups) into world-frame vertices.
  const aiScene* scene =
      importer.ReadFile(name, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (scene == nullptr)
    throw InputError(name, "", std::string("unreadable mesh: ") + importer.GetErrorString());
  sim::TriangleMesh out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      out.add_vertex(Eigen::Vector3f(p.x, p.y, p.z));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.add_triangle(base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2],
                       label);
    }
  }
  if (out.empty()) throw InputError(name, "", "mesh has no triangles");
  return out;
}

}  // namespace rownav::io
