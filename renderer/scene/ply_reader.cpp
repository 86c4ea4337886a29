// A small Stanford PLY reader: ascii, binary_little_endian and binary_big_endian; vertex
// properties x y z, nx ny nz, u v (or s t, texture_u texture_v), any others skipped; faces as
// a `vertex_indices` (or `vertex_index`) list, polygons triangulated as fans. Other elements
// are skipped. Errors name the file and what was expected.
#include "mesh_io.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace lobe::scene {
namespace {

enum class Fmt { Ascii, BinLE, BinBE };

struct Property {
  std::string name, type; // scalar type, or the item type of a list
  std::string count_type; // non-empty for lists
};
struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> props;
};

size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// Reads one value of type `t` as double.
class ValueReader {
public:
  ValueReader(std::istream& in, Fmt fmt) : in_(in), fmt_(fmt) {}
  bool read(const std::string& t, double& out) {
    if (fmt_ == Fmt::Ascii) return static_cast<bool>(in_ >> out);
    size_t n = type_size(t);
    unsigned char b[8];
    if (!in_.read(reinterpret_cast<char*>(b), std::streamsize(n))) return false;
    bool swap = (fmt_ == Fmt::BinBE) != (std::endian::native == std::endian::big);
    if (swap)
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    out = decode(t, b);
    return true;
  }

private:
  static double decode(const std::string& t, const unsigned char* b) {
    auto get = [&](auto v) {
      std::memcpy(&v, b, sizeof v);
      return static_cast<double>(v);
    };
    if (t == "char" || t == "int8") return get(int8_t{});
    if (t == "uchar" || t == "uint8") return get(uint8_t{});
    if (t == "short" || t == "int16") return get(int16_t{});
    if (t == "ushort" || t == "uint16") return get(uint16_t{});
    if (t == "int" || t == "int32") return get(int32_t{});
    if (t == "uint" || t == "uint32") return get(uint32_t{});
    if (t == "float" || t == "float32") return get(float{});
    return get(double{});
  }
  std::istream& in_;
  Fmt fmt_;
};

std::string parse_header(std::istream& in, Fmt& fmt, std::vector<Element>& elems) {
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0)
    return "not a PLY file (no 'ply' magic)";
  int lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    std::string at = "header line " + std::to_string(lineno) + ": ";
    if (kw == "end_header") return "";
    if (kw == "comment" || kw == "obj_info" || kw.empty()) continue;
    if (kw == "format") {
      std::string f;
      ls >> f;
      if (f == "ascii")
        fmt = Fmt::Ascii;
      else if (f == "binary_little_endian")
        fmt = Fmt::BinLE;
      else if (f == "binary_big_endian")
        fmt = Fmt::BinBE;
      else
        return at + "unknown format '" + f + "'";
    } else if (kw == "element") {
      Element e;
      if (!(ls >> e.name >> e.count)) return at + "expected 'element <name> <count>'";
      elems.push_back(e);
    } else if (kw == "property") {
      if (elems.empty()) return at + "property before any element";
      Property p;
      std::string t;
      ls >> t;
      if (t == "list")
        ls >> p.count_type >> p.type >> p.name;
      else
        p.type = t, ls >> p.name;
      if (type_size(p.type) == 0 || (!p.count_type.empty() && type_size(p.count_type) == 0))
        return at + "unknown property type in '" + line + "'";
      elems.back().props.push_back(p);
    } else {
      return at + "unexpected '" + kw + "'";
    }
  }
  return "header has no end_header";
}

int vertex_slot(const std::string& n) {
  static const char* names[][2] = {{"x", ""},  {"y", ""},  {"z", ""},  {"nx", ""},
                                   {"ny", ""}, {"nz", ""}, {"u", "s"}, {"v", "t"}};
  for (int i = 0; i < 8; ++i)
    if (n == names[i][0] || (names[i][1][0] && n == names[i][1])) return i;
  if (n == "texture_u") return 6;
  if (n == "texture_v") return 7;
  return -1;
}

} // namespace

std::string load_ply(const std::string& path, Mesh& mesh) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return path + ": cannot open PLY file";
  Fmt fmt = Fmt::Ascii;
  std::vector<Element> elems;
  if (std::string e = parse_header(in, fmt, elems); !e.empty()) return path + ": " + e;
  ValueReader rd(in, fmt);
  mesh = Mesh{};
  for (const Element& el : elems) {
    bool is_vertex = el.name == "vertex", is_face = el.name == "face";
    bool has_n = false, has_uv = false;
    for (const Property& p : el.props) {
      int s = vertex_slot(p.name);
      has_n |= is_vertex && s >= 3 && s <= 5;
      has_uv |= is_vertex && s >= 6;
    }
    // An element without properties has no data to run out of: a huge count would spin (or,
    // for vertices, fill memory with (0, 0, 0)) without ever reaching the end of the file.
    if (el.props.empty() && el.count > 0)
      return path + ": element '" + el.name + "' has " + std::to_string(el.count) +
             " items but no properties";
    for (size_t i = 0; i < el.count; ++i) {
      double slot[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      for (const Property& p : el.props) {
        std::string at = path + ": element '" + el.name + "' " + std::to_string(i) +
                         ", property '" + p.name + "': ";
        double v;
        if (p.count_type.empty()) {
          if (!rd.read(p.type, v)) return at + "unexpected end of data";
          int s = vertex_slot(p.name);
          if (is_vertex && s >= 0) slot[s] = v;
          continue;
        }
        double count;
        if (!rd.read(p.count_type, count)) return at + "unexpected end of data";
        if (!(count >= 0 && count <= 4294967295.0) || count != std::floor(count))
          return at + "list length " + std::to_string(count) + " is not a count";
        std::vector<uint32_t> poly;
        for (size_t k = 0; k < size_t(count); ++k) {
          if (!rd.read(p.type, v)) return at + "unexpected end of data";
          if (!(v >= 0 && v <= 4294967295.0)) // also NaN (a float list)
            return at + "value " + std::to_string(v) + " out of range for an index";
          poly.push_back(static_cast<uint32_t>(v));
        }
        if (!is_face || (p.name != "vertex_indices" && p.name != "vertex_index")) continue;
        for (size_t k = 2; k < poly.size(); ++k)
          mesh.indices.insert(mesh.indices.end(), {poly[0], poly[k - 1], poly[k]});
      }
      if (!is_vertex) continue;
      mesh.positions.push_back({float(slot[0]), float(slot[1]), float(slot[2])});
      if (has_n) mesh.normals.push_back({float(slot[3]), float(slot[4]), float(slot[5])});
      if (has_uv) mesh.uvs.insert(mesh.uvs.end(), {float(slot[6]), float(slot[7])});
    }
  }
  if (mesh.indices.empty()) return path + ": PLY file has no faces";
  for (uint32_t idx : mesh.indices)
    if (idx >= mesh.positions.size())
      return path + ": face index " + std::to_string(idx) + " out of range (" +
             std::to_string(mesh.positions.size()) + " vertices)";
  return "";
}

} // namespace lobe::scene
