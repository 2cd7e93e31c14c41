// Writing meshes: the one Wavefront OBJ writer (synth's built-in meshes, the BCOT release export)
// and the one PLY writer (the BOP export).
#pragma once

#include <string>

#include "bcot/render/mesh.h"

namespace bcot {

// OBJ text of `mesh` (vertices as stored, i.e. mm in the template frame; triangles 1-based),
// after `comment` (one or more lines without '#', each written as a '# ' comment line). Each
// coordinate is the shortest decimal that reads back to the same float, so a mesh written and
// loaded again is the same mesh.
std::string FormatObjMesh(const Mesh& mesh, const std::string& comment);

// ASCII PLY text of `mesh` (the format of BOP's models): "element vertex" with float x, y, z as
// stored (mm) and nx, ny, nz (unit vertex normals: the area-weighted sum of the adjacent
// triangles' normals, zero at a vertex of degenerate triangles only), "element face" with a
// uchar-counted int list of 0-based vertex indices, and `comment` as "comment" header lines.
// Coordinates are written like FormatObjMesh's.
std::string FormatPlyMesh(const Mesh& mesh, const std::string& comment);

}  // namespace bcot
