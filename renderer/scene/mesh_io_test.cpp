// Mesh files: OBJ through tinyobjloader and our PLY reader (ascii and binary), written here
// by hand so the expected values are known.
#include "mesh_io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

using namespace lobe;
using namespace lobe::scene;

namespace {
std::string write_file(const std::string& name, const std::string& content) {
  auto p = std::filesystem::temp_directory_path() /
           ("lobe_mesh_test_" + std::to_string(::getpid()) + "." + name);
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}
} // namespace

TEST(MeshIo, ObjQuadIsTriangulatedWithNormals) {
  std::string path = write_file("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                            "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  Mesh m;
  ASSERT_EQ(load_mesh(path, m), "");
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.normals.size(), 4u);
  EXPECT_FLOAT_EQ(m.normals[0].z, 1.0f);
  ASSERT_EQ(m.uvs.size(), 8u);
}

TEST(MeshIo, ObjSharedPositionsSplitByNormalAndUv) {
  // Two triangles share positions 1 and 3; the second uses another normal for 1 and another uv
  // for 3, and repeats (2, n1, t2) exactly. Distinct (position, normal, uv) triples in order of
  // first use: (1,1,1) (2,1,2) (3,1,3) | (1,2,1) (3,1,4); (2,1,2) is vertex 1 again.
  std::string path = write_file("split.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                             "vn 0 0 1\nvn 0 0 -1\n"
                                             "vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n"
                                             "f 1/1/1 2/2/1 3/3/1\n"
                                             "f 1/1/2 3/4/1 2/2/1\n");
  Mesh m;
  ASSERT_EQ(load_mesh(path, m), "");
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.indices, (LargeVector<uint32_t>{0, 1, 2, 3, 4, 1}));
  ASSERT_EQ(m.normals.size(), 5u);
  EXPECT_FLOAT_EQ(m.normals[3].z, -1.0f); // position 1 with normal 2
  EXPECT_FLOAT_EQ(m.positions[3].x, 0.0f);
  EXPECT_FLOAT_EQ(m.positions[4].y, 1.0f); // position 3 with uv 4
  ASSERT_EQ(m.uvs.size(), 10u);
  EXPECT_FLOAT_EQ(m.uvs[8], 0.5f);
  EXPECT_FLOAT_EQ(m.uvs[2 * 2 + 1], 1.0f); // vertex 2 keeps uv 3 = (0, 1)
}

TEST(MeshIo, AsciiPly) {
  std::string path =
      write_file("a.ply", "ply\nformat ascii 1.0\ncomment hi\n"
                          "element vertex 4\nproperty float x\nproperty float y\n"
                          "property float z\nproperty uchar red\n"
                          "element face 1\nproperty list uchar int vertex_indices\n"
                          "end_header\n0 0 0 9\n2 0 0 9\n2 3 0 9\n0 3 0 9\n4 0 1 2 3\n");
  Mesh m;
  ASSERT_EQ(load_mesh(path, m), "");
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_FLOAT_EQ(m.positions[2].y, 3.0f);
  ASSERT_EQ(m.indices.size(), 6u); // fan: 0 1 2, 0 2 3
  EXPECT_EQ(m.indices[3], 0u);
  EXPECT_EQ(m.indices[5], 3u);
  EXPECT_TRUE(m.normals.empty());
}

TEST(MeshIo, BinaryLittleEndianPly) {
  std::string data = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                     "property float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                     "property float nz\nelement face 1\nproperty list uchar uint vertex_indices\n"
                     "end_header\n";
  float v[3][6] = {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1}};
  data.append(reinterpret_cast<const char*>(v), sizeof v); // this machine is little-endian
  unsigned char n = 3;
  uint32_t idx[3] = {0, 1, 2};
  data.append(reinterpret_cast<const char*>(&n), 1);
  data.append(reinterpret_cast<const char*>(idx), sizeof idx);
  Mesh m;
  ASSERT_EQ(load_mesh(write_file("b.ply", data), m), "");
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_FLOAT_EQ(m.positions[1].x, 1.0f);
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_FLOAT_EQ(m.normals[2].z, 1.0f);
  EXPECT_EQ(m.indices.size(), 3u);
}

TEST(MeshIo, PlyErrorsAreLocated) {
  Mesh m;
  std::string bad = write_file("bad.ply", "ply\nformat ascii 1.0\nelement vertex 2\n"
                                          "property float x\nproperty float y\nproperty float z\n"
                                          "element face 1\nproperty list uchar int vertex_indices\n"
                                          "end_header\n0 0 0\n1 0 0\n3 0 1 7\n");
  EXPECT_NE(load_mesh(bad, m).find("face index 7 out of range"), std::string::npos);
  std::string trunc = write_file("trunc.ply", "ply\nformat ascii 1.0\nelement vertex 2\n"
                                              "property float x\nend_header\n1\n");
  EXPECT_NE(load_mesh(trunc, m).find("element 'vertex' 1, property 'x': unexpected end of data"),
            std::string::npos);
  EXPECT_NE(load_mesh(write_file("x.stl", ""), m).find("unknown mesh format"), std::string::npos);
}

TEST(MeshIo, TransformRotatesNormals) {
  Mesh m;
  m.positions = {{1, 0, 0}};
  m.normals = {{1, 0, 0}};
  // Non-uniform scale: a normal of the plane x + y = const must stay perpendicular to it.
  m.normals = {{0.70710678f, 0.70710678f, 0}};
  transform_mesh(m, Mat4::scale({2, 1, 1}));
  // Plane x + y = c scaled by 2 in x becomes x/2 + y = c, normal ~ (1/2, 1, 0) normalised.
  EXPECT_NEAR(m.normals[0].x, 0.5f / std::sqrt(1.25f), 1e-6);
  EXPECT_NEAR(m.normals[0].y, 1.0f / std::sqrt(1.25f), 1e-6);
  EXPECT_FLOAT_EQ(m.positions[0].x, 2.0f);
}

// Inputs the fuzz targets (fuzz/) and their review turned up: each read out of bounds, hit
// undefined behaviour or never finished before the checks.
TEST(MeshIo, ObjIndicesOutOfRangeAreErrors) {
  Mesh m;
  std::string e = load_mesh(write_file("oob.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), m);
  EXPECT_NE(e.find("face vertex index 9 out of range (3 vertices)"), std::string::npos) << e;
  e = load_mesh(write_file("oobn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n"),
                m);
  EXPECT_NE(e.find("face normal index 4 out of range (1 normals)"), std::string::npos) << e;
  e = load_mesh(write_file("oobt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n"), m);
  EXPECT_NE(e.find("face texcoord index 2 out of range (1 texcoords)"), std::string::npos) << e;
  // Relative indices reaching before the first vertex.
  e = load_mesh(write_file("oobrel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"), m);
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;
}

TEST(MeshIo, PlyBadListsAndEmptyElementsAreErrors) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                           "property float y\nproperty float z\n";
  Mesh m;
  std::string e = load_mesh(
      write_file("neg.ply", head + "element face 1\nproperty list char int vertex_indices\n"
                                   "end_header\n0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n"),
      m);
  EXPECT_NE(e.find("list length -1.000000 is not a count"), std::string::npos) << e;
  e = load_mesh(
      write_file("negidx.ply", head + "element face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
      m);
  EXPECT_NE(e.find("value -1.000000 out of range for an index"), std::string::npos) << e;
  e = load_mesh(
      write_file("fidx.ply", head + "element face 1\nproperty list float float vertex_indices\n"
                                    "end_header\n0 0 0\n1 0 0\n0 1 0\n2.5 0 1 2\n"),
      m);
  EXPECT_NE(e.find("list length 2.500000 is not a count"), std::string::npos) << e;
  // No properties: 10^15 items would take days (and, as vertices, all memory).
  e = load_mesh(write_file("noprop.ply", "ply\nformat ascii 1.0\nelement junk 1000000000000000\n"
                                         "end_header\n"),
                m);
  EXPECT_NE(e.find("element 'junk' has 1000000000000000 items but no properties"),
            std::string::npos)
      << e;
}

// Quads are split along the shorter diagonal (as tinyobjloader's ObjReader splits them), on the
// streaming path that reads them.
TEST(MeshIo, ObjQuadsSplitAlongTheShorterDiagonal) {
  Mesh m;
  // Diagonal 1-3 (length^2 2) is shorter than 0-2 (10): triangles 0 1 3 and 1 2 3, whose
  // vertices are numbered in order of first use (0 1 3 2), so 0 1 2 and 1 3 2.
  ASSERT_EQ(load_mesh(write_file("q13.obj", "v 0 0 0\nv 1 0 0\nv 3 1 0\nv 0 1 0\nf 1 2 3 4\n"), m),
            "");
  EXPECT_EQ(m.indices, (LargeVector<uint32_t>{0, 1, 2, 1, 3, 2}));
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_FLOAT_EQ(m.positions[2].y, 1.0f); // the file's fourth vertex, (0, 1, 0)
  EXPECT_FLOAT_EQ(m.positions[3].x, 3.0f); // its third, (3, 1, 0)
  // Diagonal 0-2 (2) shorter than 1-3 (13): 0 1 2 and 0 2 3.
  ASSERT_EQ(load_mesh(write_file("q02.obj", "v 0 0 0\nv 2 0 0\nv 1 1 0\nv 0 3 0\nf 1 2 3 4\n"), m),
            "");
  EXPECT_EQ(m.indices, (LargeVector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(MeshIo, ObjRelativeIndicesAndLateNormals) {
  Mesh m;
  // -1 is the last vertex read so far; the second face's -3 -2 -1 are vertices 4 5 6.
  ASSERT_EQ(load_mesh(write_file("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                            "v 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\n"),
                      m),
            "");
  EXPECT_EQ(m.indices, (LargeVector<uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_FLOAT_EQ(m.positions[3].z, 1.0f);
  // A positive index may name a normal written after the face.
  ASSERT_EQ(load_mesh(write_file("late.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n"
                                             "vn 0 0 -1\n"),
                      m),
            "");
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_FLOAT_EQ(m.normals[2].z, -1.0f);
}

// A polygon of five or more corners is triangulated by ObjReader (the whole file is read again
// that way): a convex pentagon is three triangles over its five corners.
TEST(MeshIo, ObjPentagonIsTriangulated) {
  Mesh m;
  ASSERT_EQ(load_mesh(write_file("pent.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\n"
                                             "f 1 2 3 4 5\nf 1 2 3\n"),
                      m),
            "");
  EXPECT_EQ(m.indices.size(), 12u);
  EXPECT_EQ(m.positions.size(), 5u);
}

TEST(MeshIo, ObjIndexErrorsNameTheFace) {
  Mesh m;
  std::string e = load_mesh(write_file("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), m);
  EXPECT_NE(e.find("face vertex index 0 out of range (3 vertices), in face 1"), std::string::npos)
      << e;
  e = load_mesh(write_file("face2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n"), m);
  EXPECT_NE(e.find("face vertex index 4 out of range (3 vertices), in face 2"), std::string::npos)
      << e;
  e = load_mesh(write_file("relq.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -3 -4\n"), m);
  EXPECT_NE(e.find("face vertex index -4 out of range (3 vertices), in face 2"), std::string::npos)
      << e;
  e = load_mesh(write_file("nofile.obj", ""), m);
  EXPECT_NE(e.find("no faces"), std::string::npos) << e;
  e = load_mesh("/nonexistent/dir/x.obj", m);
  EXPECT_NE(e.find("/nonexistent/dir/x.obj: cannot read OBJ file"), std::string::npos) << e;
}
