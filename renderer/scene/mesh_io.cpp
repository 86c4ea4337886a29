// OBJ loading through tinyobjloader and shared mesh helpers (see mesh_io.h).
#include "mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace lobe::scene {

static std::string extension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string load_mesh(const std::string& path, Mesh& mesh) {
  std::string ext = extension(path);
  if (ext == "obj") return load_obj(path, mesh);
  if (ext == "ply") return load_ply(path, mesh);
  return path + ": unknown mesh format (expected .obj or .ply)";
}

// OBJ indexes positions, normals and uvs separately; Embree wants one index per vertex, so
// each distinct (position, normal, uv) triple becomes one vertex.
std::string load_obj(const std::string& path, Mesh& mesh) {
  tinyobj::ObjReaderConfig cfg;
  cfg.triangulate = true;
  cfg.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, cfg)) {
    std::string e = reader.Error();
    while (!e.empty() && e.back() == '\n') e.pop_back();
    return path + ": " + (e.empty() ? "cannot read OBJ file" : e);
  }
  const auto& a = reader.GetAttrib();
  bool has_n = !a.normals.empty(), has_uv = !a.texcoords.empty();
  mesh = Mesh{};
  // tinyobjloader resolves relative (negative) indices but does not check the range.
  const size_t nv = a.vertices.size() / 3, nn = a.normals.size() / 3, nt = a.texcoords.size() / 2;
  auto bad = [&](const char* what, int i, size_t n, const char* plural) {
    return path + ": face " + what + " index " + std::to_string(i < 0 ? i : i + 1) +
           " out of range (" + std::to_string(n) + " " + plural + ")";
  };
  // Vertex of each distinct (position, normal, uv) triple, numbered in order of first use.
  // Most files use one normal/uv per position: the first vertex made from each position is
  // found through an array; triples that differ from it go to a hash map.
  constexpr uint32_t kNone = ~0u;
  std::vector<uint32_t> first(nv, kNone);
  std::vector<std::pair<int, int>> made; // (normal, uv) of each vertex made
  struct KeyHash {
    size_t operator()(const std::tuple<int, int, int>& k) const {
      uint64_t h = uint64_t(uint32_t(std::get<0>(k))) * 0x9e3779b97f4a7c15ull;
      h ^= (uint64_t(uint32_t(std::get<1>(k))) + 0x7f4a7c15u) * 0xbf58476d1ce4e5b9ull;
      h ^= (uint64_t(uint32_t(std::get<2>(k))) + 0x94d049bbu) * 0x94d049bb133111ebull;
      return size_t(h ^ (h >> 31));
    }
  };
  std::unordered_map<std::tuple<int, int, int>, uint32_t, KeyHash> others;
  size_t total = 0;
  for (const auto& shape : reader.GetShapes()) total += shape.mesh.indices.size();
  mesh.indices.reserve(total);
  for (const auto& shape : reader.GetShapes()) {
    for (const auto& idx : shape.mesh.indices) {
      if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv)
        return bad("vertex", idx.vertex_index, nv, "vertices");
      if (has_n && idx.normal_index >= 0 && size_t(idx.normal_index) >= nn)
        return bad("normal", idx.normal_index, nn, "normals");
      if (has_uv && idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt)
        return bad("texcoord", idx.texcoord_index, nt, "texcoords");
      const int ni = has_n ? idx.normal_index : -1, ti = has_uv ? idx.texcoord_index : -1;
      uint32_t& f = first[size_t(idx.vertex_index)];
      uint32_t* slot = &f;
      if (f != kNone && made[f] != std::make_pair(ni, ti))
        slot = &others.try_emplace(std::make_tuple(idx.vertex_index, ni, ti), kNone).first->second;
      if (*slot == kNone) {
        uint32_t v = static_cast<uint32_t>(mesh.positions.size());
        const float* p = &a.vertices[3 * size_t(idx.vertex_index)];
        mesh.positions.push_back({p[0], p[1], p[2]});
        if (has_n) {
          Vec3 n{0, 0, 0};
          if (ni >= 0) {
            const float* q = &a.normals[3 * size_t(ni)];
            n = {q[0], q[1], q[2]};
          }
          mesh.normals.push_back(n);
        }
        if (has_uv) {
          float u = 0, w = 0;
          if (ti >= 0) {
            u = a.texcoords[2 * size_t(ti)];
            w = a.texcoords[2 * size_t(ti) + 1];
          }
          mesh.uvs.push_back(u);
          mesh.uvs.push_back(w);
        }
        made.emplace_back(ni, ti);
        *slot = v;
      }
      mesh.indices.push_back(*slot);
    }
  }
  if (mesh.indices.empty()) return path + ": OBJ file has no faces";
  return "";
}

void transform_mesh(Mesh& mesh, const Mat4& m) {
  for (Vec3& p : mesh.positions) p = m.point(p);
  for (Vec3& n : mesh.normals) n = m.normal(n);
}

} // namespace lobe::scene
