#include "pipeline/rig_frames.h"

#include <filesystem>

#include "core/check.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_rig.h"
#include "pose/animation.h"
#include "pose/skinning.h"

namespace skinslide {

RigClip rig_clip(const MeshFile& character, const RigOptions& options) {
  SKINSLIDE_CHECK(character.gltf != nullptr, "rig_clip needs a glTF character");
  RigClip clip;
  clip.rig = gltf_rig(*character.gltf, character.path);
  clip.animation = find_animation(clip.rig, options.animation, character.path);
  const Animation& a = clip.rig.animations[clip.animation];
  clip.times = options.fps > 0 ? fps_times(a, options.fps) : keyframe_times(a);
  if (clip.times.empty()) clip.times.push_back(a.start);  // a clip without channels: its rest
  const std::string stem = std::filesystem::path(character.path).stem().string();
  const std::size_t width = std::max<std::size_t>(4, std::to_string(clip.times.size() - 1).size());
  for (std::size_t k = 0; k < clip.times.size(); ++k) {
    std::string number = std::to_string(k);
    clip.names.push_back(stem + "." + std::string(width - number.size(), '0') + number);
  }
  return clip;
}

MeshFile rig_frame(const MeshFile& character, const RigClip& clip, std::size_t k) {
  SKINSLIDE_CHECK(k < clip.times.size(), "frame index out of range");
  const Rig& rig = clip.rig;
  // In the mesh node's space at rest (glTF ignores that node's transform for skinning, and a
  // static copy is shown through it); an unskinned mesh's node motion is kept relative to it.
  const Pose local = node_space_pose_at(rig, &rig.animations[clip.animation], clip.times[k]);
  return posed_gltf_file(character, local.positions, local.normals);
}

}  // namespace skinslide
