// glTF 2.0 (.gltf + .bin / data URIs, and .glb) in and out. The only tinygltf user.
#pragma once

#include <string>

#include "io/mesh_file.h"

namespace skinslide {

/// Reads the chosen mesh of a glTF/GLB file: all triangle primitives in primitive order, vertices
/// welded by exact position for connectivity (MeshFile::mesh), the document kept for writing.
/// \throw Error(Input) naming the path (and mesh/accessor) on anything malformed or unsupported.
MeshFile read_gltf_file(const std::string& path, const MeshReadOptions& options);

/// Writes `frame`'s document with POSITION (and NORMAL/TANGENT) changed for the slid vertices.
/// \throw Error(Output) when the file cannot be written.
void write_gltf_file(const MeshFile& frame, const SlidVertices& slid, const std::string& out_path);

}  // namespace skinslide
