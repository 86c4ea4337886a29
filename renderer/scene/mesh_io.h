// Triangle meshes from files: Wavefront OBJ through tinyobjloader (Debian's
// libtinyobjloader-dev), Stanford PLY through a small reader of our own (ply_reader.cpp;
// bookworm packages no C++ PLY library).
#pragma once

#include "scene.h"

#include <string>

namespace lobe::scene {

// Loads `path` (.obj or .ply) into `mesh` (object space). Returns "" or an error naming the
// file and, where known, the line or element.
std::string load_mesh(const std::string& path, Mesh& mesh);
std::string load_obj(const std::string& path, Mesh& mesh);
std::string load_ply(const std::string& path, Mesh& mesh);

// Applies a transform to positions and normals in place.
void transform_mesh(Mesh& mesh, const Mat4& m);

} // namespace lobe::scene
