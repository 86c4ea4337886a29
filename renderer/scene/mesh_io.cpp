// OBJ loading through tinyobjloader and shared mesh helpers (see mesh_io.h).
#include "mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
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

namespace {

// One corner of a triangle: 0-based position, normal and uv indices (-1: none).
struct Corner {
  int v, n, t;
};

// An OBJ file's attributes as read and its faces as triangle corners.
struct ObjData {
  LargeVector<float> v, n, t; // xyz, xyz, uv
  LargeVector<Corner> corners;
};

// How many lines of each kind an OBJ file has (ok false when it cannot be read).
struct ObjCounts {
  size_t v = 0, vn = 0, vt = 0, f = 0;
  bool ok = false;
};

ObjCounts count_lines(const std::string& path) {
  ObjCounts c;
  std::ifstream in(path, std::ios::binary);
  if (!in) return c;
  std::vector<char> buf(size_t(1) << 20);
  size_t at_line = 0; // characters of the current line seen so far (0, 1 or 2+)
  char head[2] = {0, 0};
  auto line_done = [&] {
    if (head[0] == 'v') {
      if (head[1] == ' ' || head[1] == '\t')
        ++c.v;
      else if (head[1] == 'n')
        ++c.vn;
      else if (head[1] == 't')
        ++c.vt;
    } else if (head[0] == 'f' && (head[1] == ' ' || head[1] == '\t')) {
      ++c.f;
    }
    at_line = 0, head[0] = head[1] = 0;
  };
  while (in) {
    in.read(buf.data(), std::streamsize(buf.size()));
    size_t got = size_t(in.gcount());
    const char* p = buf.data();
    const char* end = p + got;
    while (p < end) {
      if (at_line < 2) { // the first two characters of a line
        head[at_line++] = *p;
        if (*p++ == '\n') line_done();
        continue;
      }
      const void* nl = std::memchr(p, '\n', size_t(end - p));
      if (!nl) break;
      p = static_cast<const char*>(nl) + 1;
      line_done();
    }
  }
  if (at_line) line_done();
  c.ok = in.eof();
  return c;
}

// OBJ indexes positions, normals and uvs separately; Embree wants one index per vertex, so
// each distinct (position, normal, uv) triple becomes one vertex, numbered in order of first
// use. Most files use one normal/uv per position: the first vertex made from each position is
// found through an array; triples that differ from it go to a hash map.
void build_mesh(const ObjData& d, Mesh& mesh) {
  const bool has_n = !d.n.empty(), has_uv = !d.t.empty();
  const size_t nv = d.v.size() / 3;
  mesh = Mesh{};
  constexpr uint32_t kNone = ~0u;
  LargeVector<uint32_t> first(nv, kNone);
  LargeVector<std::pair<int, int>> made; // (normal, uv) of each vertex made
  struct KeyHash {
    size_t operator()(const std::tuple<int, int, int>& k) const {
      uint64_t h = uint64_t(uint32_t(std::get<0>(k))) * 0x9e3779b97f4a7c15ull;
      h ^= (uint64_t(uint32_t(std::get<1>(k))) + 0x7f4a7c15u) * 0xbf58476d1ce4e5b9ull;
      h ^= (uint64_t(uint32_t(std::get<2>(k))) + 0x94d049bbu) * 0x94d049bb133111ebull;
      return size_t(h ^ (h >> 31));
    }
  };
  std::unordered_map<std::tuple<int, int, int>, uint32_t, KeyHash> others;
  mesh.indices.reserve(d.corners.size());
  mesh.positions.reserve(nv);
  if (has_n) mesh.normals.reserve(nv);
  if (has_uv) mesh.uvs.reserve(2 * nv);
  made.reserve(nv);
  for (const Corner& c : d.corners) {
    const int ni = has_n ? c.n : -1, ti = has_uv ? c.t : -1;
    uint32_t& f = first[size_t(c.v)];
    uint32_t* slot = &f;
    if (f != kNone && made[f] != std::make_pair(ni, ti))
      slot = &others.try_emplace(std::make_tuple(c.v, ni, ti), kNone).first->second;
    if (*slot == kNone) {
      uint32_t v = static_cast<uint32_t>(mesh.positions.size());
      const float* p = &d.v[3 * size_t(c.v)];
      mesh.positions.push_back({p[0], p[1], p[2]});
      if (has_n) {
        Vec3 n{0, 0, 0};
        if (ni >= 0) {
          const float* q = &d.n[3 * size_t(ni)];
          n = {q[0], q[1], q[2]};
        }
        mesh.normals.push_back(n);
      }
      if (has_uv) {
        float u = 0, w = 0;
        if (ti >= 0) {
          u = d.t[2 * size_t(ti)];
          w = d.t[2 * size_t(ti) + 1];
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

// The whole file through tinyobjloader's ObjReader, which triangulates polygons of five and more
// corners (ear clipping); used for files that have such polygons.
std::string read_obj_polygons(const std::string& path, ObjData& d) {
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
  d = ObjData{};
  d.v.assign(a.vertices.begin(), a.vertices.end());
  d.n.assign(a.normals.begin(), a.normals.end());
  d.t.assign(a.texcoords.begin(), a.texcoords.end());
  // tinyobjloader resolves relative (negative) indices but does not check the range.
  const size_t nv = d.v.size() / 3, nn = d.n.size() / 3, nt = d.t.size() / 2;
  auto bad = [&](const char* what, int i, size_t n, const char* plural) {
    return path + ": face " + what + " index " + std::to_string(i < 0 ? i : i + 1) +
           " out of range (" + std::to_string(n) + " " + plural + ")";
  };
  for (const auto& shape : reader.GetShapes())
    for (const auto& idx : shape.mesh.indices) {
      if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv)
        return bad("vertex", idx.vertex_index, nv, "vertices");
      if (nn && idx.normal_index >= 0 && size_t(idx.normal_index) >= nn)
        return bad("normal", idx.normal_index, nn, "normals");
      if (nt && idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt)
        return bad("texcoord", idx.texcoord_index, nt, "texcoords");
      d.corners.push_back({idx.vertex_index, idx.normal_index, idx.texcoord_index});
    }
  return "";
}

// The file through tinyobjloader's streaming parser, with faces triangulated as they are read:
// 3 to 4 times faster than ObjReader on large files (bench/embree_compare's 39 MB OBJ: 0.43-0.62
// s -> 0.15 s), which keeps per-face records and grows them copy by copy. Quads are split along
// their shorter diagonal, as ObjReader splits them; a polygon of five or more corners (or a quad
// whose corners come later in the file) sets `polygons`, and the caller reads the file with
// ObjReader instead. Relative (negative) indices resolve against what has been read so far;
// positive ones are checked once the whole file is read, as ObjReader's are.
struct Streamed {
  ObjData* d;
  LargeVector<uint32_t> face_of; // per triangle, its face's number (1-based), for errors
  std::string error;             // a relative index before the start, with its face
  uint32_t faces = 0;
  bool polygons = false;
};

std::string index_error(const char* what, int64_t i, size_t n, const char* plural, uint32_t face) {
  return std::string("face ") + what + " index " + std::to_string(i) + " out of range (" +
         std::to_string(n) + " " + plural + "), in face " + std::to_string(face);
}

void on_face(void* user, tinyobj::index_t* idx, int count) {
  Streamed& s = *static_cast<Streamed*>(user);
  ++s.faces;
  if (!s.error.empty() || s.polygons || count < 3) return; // (ObjReader skips degenerate faces)
  if (count > 4) {
    s.polygons = true;
    return;
  }
  ObjData& d = *s.d;
  const size_t counts[3] = {d.v.size() / 3, d.n.size() / 3, d.t.size() / 2};
  static constexpr const char* kWhat[3][2] = {
      {"vertex", "vertices"}, {"normal", "normals"}, {"texcoord", "texcoords"}};
  Corner c[4];
  for (int k = 0; k < count; ++k) {
    const int raw[3] = {idx[k].vertex_index, idx[k].normal_index, idx[k].texcoord_index};
    int64_t r[3];
    for (int a = 0; a < 3; ++a) {
      // OBJ's numbering: 1-based; negative counts back from the last element read; 0 (or
      // nothing written) is no normal or uv, and no position at all.
      r[a] = raw[a] > 0 ? int64_t(raw[a]) - 1 : raw[a] < 0 ? int64_t(counts[a]) + raw[a] : -1;
      if ((raw[a] < 0 && r[a] < 0) || (a == 0 && raw[a] == 0)) {
        s.error = index_error(kWhat[a][0], raw[a], counts[a], kWhat[a][1], s.faces);
        return;
      }
    }
    c[k] = Corner{int(r[0]), int(r[1]), int(r[2])};
  }
  if (count == 4) {
    for (const Corner& x : c)
      if (size_t(x.v) >= counts[0]) { // a corner not read yet: no diagonal to measure
        s.polygons = true;
        return;
      }
    auto dist2 = [&](const Corner& a, const Corner& b) {
      const float *p = &d.v[3 * size_t(a.v)], *q = &d.v[3 * size_t(b.v)];
      float x = q[0] - p[0], y = q[1] - p[1], z = q[2] - p[2];
      return x * x + y * y + z * z;
    };
    if (dist2(c[0], c[2]) < dist2(c[1], c[3]))
      d.corners.insert(d.corners.end(), {c[0], c[1], c[2], c[0], c[2], c[3]});
    else
      d.corners.insert(d.corners.end(), {c[0], c[1], c[3], c[1], c[2], c[3]});
    s.face_of.insert(s.face_of.end(), {s.faces, s.faces});
    return;
  }
  d.corners.insert(d.corners.end(), c, c + 3);
  s.face_of.push_back(s.faces);
}

// After the whole file: every index within what the file defines (a normal or uv index in a
// file without any is ignored, as ObjReader ignores it).
std::string check_indices(Streamed& s) {
  ObjData& d = *s.d;
  const size_t nv = d.v.size() / 3, nn = d.n.size() / 3, nt = d.t.size() / 2;
  for (size_t i = 0; i < d.corners.size(); ++i) {
    Corner& c = d.corners[i];
    uint32_t face = s.face_of[i / 3];
    if (size_t(c.v) >= nv) return index_error("vertex", int64_t(c.v) + 1, nv, "vertices", face);
    if (!nn) c.n = -1;
    if (!nt) c.t = -1;
    if (c.n >= 0 && size_t(c.n) >= nn)
      return index_error("normal", int64_t(c.n) + 1, nn, "normals", face);
    if (c.t >= 0 && size_t(c.t) >= nt)
      return index_error("texcoord", int64_t(c.t) + 1, nt, "texcoords", face);
  }
  return "";
}

} // namespace

std::string load_obj(const std::string& path, Mesh& mesh) {
  ObjData d;
  Streamed s{&d};
  {
    // The lines are counted by kind first (a pass over the file in 1 MB pieces) and the arrays
    // reserved at once (LargeVectors: in huge pages): grown by doubling, they were copied at
    // every step and each 4 kB page of the new copy faulted in on first touch (a third of the
    // load's time in a virtual machine, where faults are dear).
    ObjCounts lines = count_lines(path);
    if (!lines.ok) return path + ": cannot read OBJ file";
    d.v.reserve(3 * lines.v);
    d.n.reserve(3 * lines.vn);
    d.t.reserve(2 * lines.vt);
    d.corners.reserve(3 * lines.f); // triangles; a file of quads grows it once
    s.face_of.reserve(lines.f);
    std::ifstream in(path, std::ios::binary);
    if (!in) return path + ": cannot read OBJ file";
    tinyobj::callback_t cb;
    cb.vertex_cb = [](void* u, float x, float y, float z, float) {
      auto& v = static_cast<Streamed*>(u)->d->v;
      v.insert(v.end(), {x, y, z});
    };
    cb.normal_cb = [](void* u, float x, float y, float z) {
      auto& n = static_cast<Streamed*>(u)->d->n;
      n.insert(n.end(), {x, y, z});
    };
    cb.texcoord_cb = [](void* u, float x, float y, float) {
      auto& t = static_cast<Streamed*>(u)->d->t;
      t.insert(t.end(), {x, y});
    };
    cb.index_cb = on_face;
    std::string warn, err;
    if (!tinyobj::LoadObjWithCallback(in, cb, &s, nullptr, &warn, &err)) {
      while (!err.empty() && err.back() == '\n') err.pop_back();
      return path + ": " + (err.empty() ? "cannot read OBJ file" : err);
    }
  }
  if (!s.error.empty()) return path + ": " + s.error;
  if (s.polygons) {
    std::string e = read_obj_polygons(path, d);
    if (!e.empty()) return e;
  } else if (std::string e = check_indices(s); !e.empty()) {
    return path + ": " + e;
  }
  if (d.corners.empty()) return path + ": OBJ file has no faces";
  build_mesh(d, mesh);
  return "";
}

void transform_mesh(Mesh& mesh, const Mat4& m) {
  for (Vec3& p : mesh.positions) p = m.point(p);
  for (Vec3& n : mesh.normals) n = m.normal(n);
}

} // namespace lobe::scene
