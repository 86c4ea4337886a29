// OBJ loading through tinyobjloader and shared mesh helpers (see mesh_io.h).
#include "mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <map>
#include <tuple>

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
  std::map<std::tuple<int, int, int>, uint32_t> remap;
  mesh = Mesh{};
  // tinyobjloader resolves relative (negative) indices but does not check the range.
  const size_t nv = a.vertices.size() / 3, nn = a.normals.size() / 3, nt = a.texcoords.size() / 2;
  auto bad = [&](const char* what, int i, size_t n, const char* plural) {
    return path + ": face " + what + " index " + std::to_string(i < 0 ? i : i + 1) +
           " out of range (" + std::to_string(n) + " " + plural + ")";
  };
  for (const auto& shape : reader.GetShapes()) {
    for (const auto& idx : shape.mesh.indices) {
      if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv)
        return bad("vertex", idx.vertex_index, nv, "vertices");
      if (has_n && idx.normal_index >= 0 && size_t(idx.normal_index) >= nn)
        return bad("normal", idx.normal_index, nn, "normals");
      if (has_uv && idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt)
        return bad("texcoord", idx.texcoord_index, nt, "texcoords");
      auto key = std::make_tuple(idx.vertex_index, has_n ? idx.normal_index : -1,
                                 has_uv ? idx.texcoord_index : -1);
      auto it = remap.find(key);
      if (it == remap.end()) {
        uint32_t v = static_cast<uint32_t>(mesh.positions.size());
        const float* p = &a.vertices[3 * size_t(idx.vertex_index)];
        mesh.positions.push_back({p[0], p[1], p[2]});
        if (has_n) {
          Vec3 n{0, 0, 0};
          if (idx.normal_index >= 0) {
            const float* q = &a.normals[3 * size_t(idx.normal_index)];
            n = {q[0], q[1], q[2]};
          }
          mesh.normals.push_back(n);
        }
        if (has_uv) {
          float u = 0, w = 0;
          if (idx.texcoord_index >= 0) {
            u = a.texcoords[2 * size_t(idx.texcoord_index)];
            w = a.texcoords[2 * size_t(idx.texcoord_index) + 1];
          }
          mesh.uvs.push_back(u);
          mesh.uvs.push_back(w);
        }
        it = remap.emplace(key, v).first;
      }
      mesh.indices.push_back(it->second);
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
