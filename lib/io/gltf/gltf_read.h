// Reading glTF 2.0 (.gltf + .bin / data URIs, and .glb): the surface skinslide slides, and the
// document kept so that a slid copy can be written (io/gltf/gltf_write.h). This header does not
// expose tinygltf (GltfDocument is defined in io/gltf/gltf_document.h, included by io/gltf/*.cpp
// only).
//
// The surface (README "glTF"): all triangle primitives (TRIANGLES, TRIANGLE_STRIP and
// TRIANGLE_FAN, expanded to triangles as the spec orders them) of one mesh, in primitive order;
// points and lines primitives are not part of it. Face f of the PolyMesh is the f-th triangle in
// that order, so patch files count triangles. Raw vertices (the elements of each primitive's
// POSITION accessor, primitives concatenated) are welded by exact position for connectivity:
// welded vertex ids follow the first raw vertex at each position. Morph targets are not applied
// here (the base POSITION is the surface; io/gltf/gltf_rig and pose/ apply them with --animation).
#pragma once

#include <string>
#include <vector>

#include "io/mesh_file.h"

namespace skinslide {

/// Reads the chosen mesh of a glTF/GLB file (GLB if the bytes start with the GLB magic): the
/// welded triangle surface (MeshFile::mesh) and the document, kept for writing.
/// `options.mesh`: empty = the only mesh; else a mesh name, or failing that an index.
/// Sparse accessors, normalized and quantized (KHR_mesh_quantization) attributes, interleaved
/// buffer views and external or data-URI buffers are read. External buffers are read only from
/// inside the file's folder or a tree of `options.allow_uri_outside` (io/gltf/gltf_uri.h), each URI
/// judged before any file is opened. Images are neither decoded nor opened.
/// \throw Error(Input) naming the path (and mesh, primitive, accessor) on anything malformed or
///        unsupported: Draco or meshopt compression, no triangle, a missing POSITION, an index or
///        element out of range, a non-finite position; with several meshes and no choice, the
///        message lists them with their primitive and vertex counts; naming the buffer and its
///        URI for a URI the rule refuses.
MeshFile read_gltf_file(const std::string& path, const MeshReadOptions& options);

/// Raw vertex -> welded vertex: raw vertices (split at UV seams) at exactly the same position are
/// one vertex, numbered in the order of their first raw copy. Exact equality: seams split
/// vertices without moving them (data/README.md), and a tolerance would risk joining genuinely
/// distinct vertices; -0 and +0 are the same coordinate. \pre finite positions
std::vector<Index> weld_positions(const Positions3& raw);

/// How many raw vertices (the POSITION elements of the mesh's triangle primitives, primitives
/// concatenated) `file`'s welded mesh was built from. \pre `file` was read by read_gltf_file.
Index gltf_raw_vertex_count(const MeshFile& file);

}  // namespace skinslide
