// glTF 2.0 (.gltf + .bin / data URIs, and .glb) in and out. With io/gltf_accessor and
// io/gltf_rig, the only tinygltf user; this header does not expose tinygltf (GltfDocument is
// defined in io/gltf_document.h, included by io/*.cpp only).
//
// The surface (README "glTF"): all triangle primitives (TRIANGLES, TRIANGLE_STRIP and
// TRIANGLE_FAN, expanded to triangles as the spec orders them) of one mesh, in primitive order;
// points and lines primitives are not part of it. Face f of the PolyMesh is the f-th triangle in
// that order, so patch files count triangles. Raw vertices (the elements of each primitive's
// POSITION accessor, primitives concatenated) are welded by exact position for connectivity:
// welded vertex ids follow the first raw vertex at each position. Morph targets are not applied
// here (the base POSITION is the surface; io/gltf_rig and pose/ apply them with --animation).
#pragma once

#include <string>
#include <vector>

#include "io/mesh_file.h"
#include "mesh/slid_vertices.h"

namespace skinslide {

/// Reads the chosen mesh of a glTF/GLB file (GLB if the bytes start with the GLB magic): the
/// welded triangle surface (MeshFile::mesh) and the document, kept for writing.
/// `options.mesh`: empty = the only mesh; else a mesh name, or failing that an index.
/// Sparse accessors, normalized and quantized (KHR_mesh_quantization) attributes, interleaved
/// buffer views and external or data-URI buffers are read. Images are not decoded.
/// \throw Error(Input) naming the path (and mesh, primitive, accessor) on anything malformed or
///        unsupported: Draco or meshopt compression, no triangle, a missing POSITION, an index or
///        element out of range, a non-finite position; with several meshes and no choice, the
///        message lists them with their primitive and vertex counts.
MeshFile read_gltf_file(const std::string& path, const MeshReadOptions& options);

/// Raw vertex -> welded vertex: raw vertices (split at UV seams) at exactly the same position are
/// one vertex, numbered in the order of their first raw copy. Exact equality: seams split
/// vertices without moving them (data/README.md), and a tolerance would risk joining genuinely
/// distinct vertices; -0 and +0 are the same coordinate. \pre finite positions
std::vector<Index> weld_positions(const Positions3& raw);

/// Writes `frame`'s document with the slid vertices moved: every raw copy of a moved welded
/// vertex gets its new position; NORMAL, and TANGENT xyz (w kept), are the frame's normals of
/// the landing triangle's raw corners interpolated with the slide's barycentric weights,
/// renormalised. Plain float accessors are edited in place (only the moved vertices' bytes
/// change); sparse, normalized or quantized ones are replaced by a new float accessor appended
/// to buffer 0. Edited accessors get exact min/max. Everything else (nodes, materials, images,
/// skins, animations, extensions, extras) is written back as tinygltf read it.
/// `out_path` ending in .glb gives a GLB; else a .gltf with its buffers as `<stem>.bin`,
/// `<stem>_1.bin`, ... beside it. External image URIs are rewritten to reach the same images
/// from the output's folder. Each file is written atomically.
/// \pre `frame` was read by read_gltf_file (or made by posed_gltf_file); `slid` samples index
///      its triangles with corner slots 0..2.
/// \throw Error(Output) when a file cannot be written.
void write_gltf_file(const MeshFile& frame, const SlidVertices& slid, const std::string& out_path);

/// A static copy of an animated `character` in a given pose: POSITION (and NORMAL, when both the
/// primitive and `raw_normals` have them) of every raw vertex replaced by the pose, the skin
/// detached from the mesh's nodes, JOINTS_n/WEIGHTS_n dropped from its primitives, and its morph
/// targets, their weights (mesh and nodes) and the weights channels of its nodes removed (a
/// viewer would otherwise deform it again; a sampler or clip left unused goes too). The welded mesh
/// takes each welded vertex's first raw copy. \param raw_positions one per raw vertex, in the mesh
/// node's space (pose/skinning.h
///        to_node_space), so that a viewer shows the pose where the animated character is.
/// \param raw_normals one per raw vertex, or empty to keep the stored normals.
MeshFile posed_gltf_file(const MeshFile& character, const Positions3& raw_positions,
                         const Positions3& raw_normals);

/// How many raw vertices (the POSITION elements of the mesh's triangle primitives, primitives
/// concatenated) `file`'s welded mesh was built from. \pre `file` was read by read_gltf_file.
Index gltf_raw_vertex_count(const MeshFile& file);

/// A static copy of `bind` (read by read_gltf_file) with its welded vertices at `positions` (#V:
/// a point cache's sample), as posed_gltf_file writes it: every raw copy at its welded vertex's
/// position; NORMAL of each raw vertex the area-weighted normal of the triangles using that raw
/// vertex, so that edges the file splits for hard shading stay hard (a cache has no normals).
MeshFile gltf_at_positions(const MeshFile& bind, const Positions3& positions);

}  // namespace skinslide
