// `skinslide compare A B`: two slid outputs compared as meshes, frame by frame. A and B are two
// folders of frames (OBJ, glTF, GLB files and PC2/MDD caches, paired by file name), two mesh
// files or two caches (sample by sample). Read through io/ (read_mesh_file, CacheReader), one
// frame of each in memory at a time; what each frame's difference is: compare/mesh_difference.h.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "compare/mesh_difference.h"
#include "io/mesh_file.h"

namespace skinslide {

struct CompareOptions {
  double tolerance = kDefaultCompareTolerance;  ///< in diagonals; >= 0
  /// A mesh (the bind) whose bounding-box diagonal distances are measured in, and whose faces
  /// are the caches' (a cache has none); empty: A's first frame's diagonal, no face check on
  /// caches.
  std::string bind;
  MeshReadOptions mesh;  ///< which mesh of a glTF holding several (`--mesh`)
};

/// One frame of A beside the same frame of B.
struct ComparedFrame {
  std::string a, b;  ///< the frames: files, or "shot.pc2 sample 3" for a cache's
  FrameDifference difference;
  std::string vertex_at;  ///< A's line of the farthest vertex, "a/f.0003.obj:125" (OBJ only)
  bool differs = false;   ///< farther than the tolerance, or a face turned
};

struct CompareResult {
  std::string a, b;
  double tolerance = 0;
  double diagonal = 0;        ///< the length distances are in
  std::string diagonal_from;  ///< whose bounding box: the bind, or A's first frame
  /// Every frame's faces compared: false once a cache is compared without a bind (no faces).
  bool faces_checked = false;
  std::vector<ComparedFrame> frames;  ///< in file name order; a cache's in sample order

  std::size_t differing() const;  ///< frames that differ
  /// The frame with the largest vertex distance (the first of equals); -1 for no frame.
  long long largest() const;
};

/// Compares outputs A and B (paths: two folders, two mesh files or two caches of one format).
/// `frame_done` (optional) is called with each frame once compared, in order.
/// \throw Error(Usage) for a tolerance below 0 or not finite, or a folder compared with a file,
///        a mesh with a cache; Error(Input) naming both files for: a path that does not exist or
///        cannot be read, a folder with no frame, a frame in one folder and not in the other (the
///        counts and the first missing names), a frame of another vertex count or other faces
///        than its pair (or than the bind), caches of different formats, sample counts or frame
///        numbers, a diagonal of zero length.
CompareResult compare_outputs(const std::string& a, const std::string& b,
                              const CompareOptions& options,
                              const std::function<void(const ComparedFrame&)>& frame_done = {});

}  // namespace skinslide
