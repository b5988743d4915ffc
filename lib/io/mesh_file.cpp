#include "io/mesh_file.h"

#include <algorithm>

#include "core/error.h"
#include "core/file_extension.h"
#include "io/atomic_write.h"
#include "io/gltf.h"
#include "io/obj_read.h"
#include "io/obj_rewrite.h"

namespace skinslide {

std::string MeshFile::where_face(Index face) const {
  if (face >= 0 && static_cast<size_t>(face) < face_lines.size())
    return path + ":" + std::to_string(face_lines[face]);
  return path + ": triangle " + std::to_string(face);
}

MeshFormat mesh_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".gltf") return MeshFormat::Gltf;
  if (ext == ".glb") return MeshFormat::Glb;
  throw Error(ErrorKind::Usage,
              path + ": unknown mesh format '" + ext + "' (expected .obj, .gltf or .glb)");
}

MeshFile read_mesh_file(const std::string& path, const MeshReadOptions& options) {
  if (mesh_format(path) != MeshFormat::Obj) return read_gltf_file(path, options);
  MeshFile file;
  file.path = path;
  file.format = mesh_format(path);
  ObjMesh obj = read_obj(path);
  file.mesh = std::move(obj.mesh);
  file.face_lines = std::move(obj.face_lines);
  file.obj = std::make_shared<const ObjText>(std::move(obj.text));
  return file;
}

void require_same_topology(const MeshFile& bind, const MeshFile& frame) {
  const PolyMesh& a = bind.mesh;
  const PolyMesh& b = frame.mesh;
  if (a.vertex_count() != b.vertex_count())
    throw_input(frame.path, 0,
                "has " + std::to_string(b.vertex_count()) + " vertices; the bind (" + bind.path +
                    ") has " + std::to_string(a.vertex_count()) +
                    ": a frame must be the bind mesh deformed");
  const Index n = std::min(a.face_count(), b.face_count());
  for (Index f = 0; f < n; ++f) {
    if (a.face_size(f) == b.face_size(f) &&
        std::equal(a.face_begin(f), a.face_begin(f) + a.face_size(f), b.face_begin(f)))
      continue;
    throw Error(ErrorKind::Input, frame.where_face(f) + ": face " + std::to_string(f) +
                                      " differs from the bind's (" + bind.where_face(f) +
                                      "): a frame must have the bind's faces");
  }
  if (a.face_count() != b.face_count())
    throw_input(frame.path, 0,
                "has " + std::to_string(b.face_count()) + " faces; the bind (" + bind.path +
                    ") has " + std::to_string(a.face_count()));
}

void release_faces(MeshFile& frame) {
  PolyMesh& m = frame.mesh;
  std::vector<Index>{0}.swap(m.face_start);
  std::vector<Index>().swap(m.face_vertices);
  std::vector<long>().swap(frame.face_lines);
}

void write_slid_mesh_file(const MeshFile& frame, const SlidVertices& slid,
                          const std::string& out_path) {
  if (frame.gltf) return write_gltf_file(frame, slid, out_path);
  Positions3 positions = apply_slide(frame.mesh.positions, slid);
  write_rewritten_obj(out_path, *frame.obj, frame.mesh.positions, positions);
}

}  // namespace skinslide
