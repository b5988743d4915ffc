// A mesh as read from a file (OBJ, glTF), with what is needed to write an edited copy of that file;
// the frames' checks against the bind. Reading and writing whatever the format: io/mesh_formats.h.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mesh/poly_mesh.h"

namespace skinslide {

struct ObjText;       // io/obj_read.h
struct GltfDocument;  // io/gltf/gltf.h

enum class MeshFormat { Obj, Gltf, Glb };

/// How to read a mesh file: which mesh of a multi-mesh glTF (`--mesh`; empty = the only one),
/// and the trees a glTF's buffers may be read from besides its own folder
/// (`--allow-uri-outside`, io/gltf/gltf_uri.h; empty = its folder only).
struct MeshReadOptions {
  std::string mesh;
  std::vector<std::string> allow_uri_outside = {};  // "= {}": `{mesh}` alone does not warn
};

/// A mesh as read from a file, with what is needed to write an edited copy of that file.
struct MeshFile {
  std::string path;
  MeshFormat format = MeshFormat::Obj;
  PolyMesh mesh;                       ///< the surface skinslide works on
  std::vector<long> face_lines;        ///< OBJ: source line of each face (1-based); else empty
  std::shared_ptr<const ObjText> obj;  ///< set for OBJ
  std::shared_ptr<const GltfDocument> gltf;  ///< set for glTF / GLB
  std::string where_face(Index face) const;  ///< "bind.obj:301" or "bind.glb: triangle 57"
};

/// Checks that `frame` has the bind's vertex count and exactly its faces.
/// \throw Error(Input) naming the frame's file, and the line or face where they first differ.
void require_same_topology(const MeshFile& bind, const MeshFile& frame);

/// Frees `frame`'s faces and their source lines, which only require_same_topology reads: sliding
/// and writing a frame need its positions and its file (about 27 MB less a frame in flight at 1M
/// vertices). Afterwards frame.mesh has no faces.
void release_faces(MeshFile& frame);

}  // namespace skinslide
