// The parsed glTF document a MeshFile keeps so that its slid copy can be written. Internal to io/:
// only io/gltf/*.cpp include this header (it pulls in tinygltf, which no other folder may see).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/file_extension.h"
#include "core/types.h"

namespace skinslide {

/// One triangle primitive of the chosen mesh, as read. Its raw vertices are the elements of its
/// POSITION accessor; they are numbered globally by concatenating the primitives in order
/// (raw id = raw_offset + element index).
struct GltfPrimitive {
  int primitive = -1;          ///< index in model.meshes[mesh].primitives
  int position_accessor = -1;  ///< POSITION
  int normal_accessor = -1;    ///< NORMAL, -1 when absent
  int tangent_accessor = -1;   ///< TANGENT, -1 when absent
  Index raw_offset = 0;        ///< global raw id of element 0
  Index raw_count = 0;         ///< POSITION count
  Index first_triangle = 0;    ///< its first triangle in the welded PolyMesh
  Index triangle_count = 0;
};

/// A glTF file as read by read_gltf_file: the model, and how the PolyMesh was built from it.
struct GltfDocument {
  tinygltf::Model model;
  bool binary = false;                    ///< read from .glb
  int mesh = -1;                          ///< the chosen mesh (index into model.meshes)
  std::vector<GltfPrimitive> primitives;  ///< the mesh's triangle primitives, in order
  std::vector<Index> welded;              ///< raw id -> welded vertex id (#raw)
  Positions3 raw_positions;               ///< POSITION of every raw vertex (#raw)
  /// The raw corners (global raw ids) of each triangle of the PolyMesh (#triangles).
  std::vector<std::array<Index, 3>> triangle_raw;
  std::vector<int> triangle_primitive;  ///< index into `primitives` of each triangle
  /// The external files read (the buffers'; never an image), resolved, in read order.
  std::vector<std::string> files_read;
};

/// True when `path` ends in .glb (any case): the reader's MeshFile::format, and what the writer
/// writes (a GLB, else a .gltf with .bin files).
inline bool has_glb_extension(const std::string& path) { return lower_extension(path) == ".glb"; }

}  // namespace skinslide
