// Writing glTF 2.0: a document read by io/gltf/gltf_read.h written back with the slid vertices
// moved, and the static copies (a posed character, a bind at a point cache's positions) that are
// written the same way. This header does not expose tinygltf.
#pragma once

#include <string>

#include "io/mesh_file.h"
#include "mesh/slid_vertices.h"

namespace skinslide {

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
/// takes each welded vertex's first raw copy.
/// \param raw_positions one per raw vertex, in the mesh node's space (pose/skinning.h
///        to_node_space), so that a viewer shows the pose where the animated character is.
/// \param raw_normals one per raw vertex, or empty to keep the stored normals.
MeshFile posed_gltf_file(const MeshFile& character, const Positions3& raw_positions,
                         const Positions3& raw_normals);

/// A static copy of `bind` (read by read_gltf_file) with its welded vertices at `positions` (#V:
/// a point cache's sample), as posed_gltf_file writes it: every raw copy at its welded vertex's
/// position; NORMAL of each raw vertex the area-weighted normal of the triangles using that raw
/// vertex, so that edges the file splits for hard shading stay hard (a cache has no normals).
MeshFile gltf_at_positions(const MeshFile& bind, const Positions3& positions);

}  // namespace skinslide
