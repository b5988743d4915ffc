#include "io/mesh_formats.h"

#include "core/error.h"
#include "core/file_extension.h"
#include "io/gltf/gltf.h"
#include "io/obj_read.h"
#include "io/obj_rewrite.h"

namespace skinslide {

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

void write_slid_mesh_file(const MeshFile& frame, const SlidVertices& slid,
                          const std::string& out_path) {
  if (frame.gltf) return write_gltf_file(frame, slid, out_path);
  Positions3 positions = apply_slide(frame.mesh.positions, slid);
  write_rewritten_obj(out_path, *frame.obj, frame.mesh.positions, positions);
}

}  // namespace skinslide
