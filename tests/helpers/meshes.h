// Tiny hand-built meshes shared by the tests.
#pragma once

#include <string>
#include <vector>

#include "mesh/poly_mesh.h"

namespace skinslide::test {

/// An n x m grid of unit quads in the z = 0 plane, vertex (i, j) = id j*(n+1)+i at (i, j, 0),
/// quad (i, j) = face j*n+i, counter-clockwise seen from +z.
PolyMesh quad_grid(int n, int m);

/// quad_grid with the faces in `holes` removed from the face list (ids of the full grid).
PolyMesh quad_grid_with_holes(int n, int m, const std::vector<Index>& holes);

/// An open tube: `around` quads around (radius 1), `along` quads along z (length `length`).
PolyMesh tube(int around, int along, double length);

/// All face ids 0..face_count-1.
std::vector<Index> all_faces(const PolyMesh& mesh);

/// A fresh empty folder in the test process's scratch folder, removed when the process exits
/// (helpers/temp_dir.h); `name` tells the tests of one process apart.
std::string temp_dir(const std::string& name);

/// Path of a file in the repository or in the shared folder (helpers/shared_data.h).
std::string source_path(const std::string& relative);
std::string shared_path(const std::string& relative);

}  // namespace skinslide::test
