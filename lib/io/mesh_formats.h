// Mesh files in and out, whatever the format (.obj, .gltf, .glb, told by the extension): the entry
// points of the run and the Python module. Each format's own reader and writer: io/obj_read.h,
// io/obj_rewrite.h, io/gltf/gltf.h.
#pragma once

#include <string>

#include "io/mesh_file.h"
#include "mesh/slid_vertices.h"

namespace skinslide {

/// Format from the file name's extension (.obj, .gltf, .glb; case-insensitive).
/// \throw Error(Usage) for any other extension.
MeshFormat mesh_format(const std::string& path);

/// Reads a mesh file. \throw Error(Input) naming the path (and line) on any malformed input.
MeshFile read_mesh_file(const std::string& path, const MeshReadOptions& options = {});

/// Writes `frame`'s file to `out_path` with the vertices of `slid` moved; everything else is
/// kept as it was. Atomic: a temporary file in the target folder, renamed when complete.
/// \throw Error(Output) when the file cannot be written.
void write_slid_mesh_file(const MeshFile& frame, const SlidVertices& slid,
                          const std::string& out_path);

}  // namespace skinslide
