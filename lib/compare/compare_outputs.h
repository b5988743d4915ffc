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
  /// Compare only the frames both sides hold (`--common`: a farm chunk against the whole run):
  /// a folder's files by name, a cache's samples by frame number (PC2) or time (MDD); the others
  /// are listed in CompareResult::only_in_a/only_in_b. False: a frame on one side only is an
  /// error.
  bool common = false;
};

/// One frame of A beside the same frame of B.
struct ComparedFrame {
  std::string a, b;  ///< the frames: files, or "shot.pc2 sample 3" for a cache's
  FrameDifference difference;
  double diagonal = 0;    ///< the length its distances are in: the bind's, else A's frame's own
  std::string vertex_at;  ///< A's line of the farthest vertex, "a/f.0003.obj:125" (OBJ only)
  bool differs = false;   ///< farther than the tolerance, or a face turned
};

struct CompareResult {
  std::string a, b;
  double tolerance = 0;
  double diagonal = 0;        ///< the bind's diagonal; 0: each frame's own (ComparedFrame)
  std::string diagonal_from;  ///< the bind's path; empty: each frame's own diagonal
  /// Every frame's faces compared: false once a cache is compared without a bind (no faces).
  bool faces_checked = false;
  std::vector<ComparedFrame> frames;  ///< in file name order; a cache's in sample order
  /// With CompareOptions::common, the frames left out as one side lacks them: folder files
  /// ("a/f.0005.obj"), cache samples ("a.pc2 sample 4 (frame 5)"), in order. Else empty.
  std::vector<std::string> only_in_a, only_in_b;

  std::size_t differing() const;  ///< frames that differ
  /// The frame with the largest vertex distance (the first of equals); -1 for no frame.
  long long largest() const;
};

/// Compares outputs A and B (paths: two folders, two mesh files or two caches of one format).
/// Each frame's distances are in the bind's diagonal, else in its own (A's frame's): a folder
/// may hold several meshes' frames, a chunk be compared with the whole shot (`common`).
/// `frame_done` (optional) is called with each frame once compared, in order.
/// \throw Error(Usage) for a tolerance below 0 or not finite, or a folder compared with a file,
///        a mesh with a cache; Error(Input) naming both files for: a path that does not exist or
///        cannot be read, a folder with no frame, a frame in one folder and not in the other (the
///        counts and the first missing names; with `common`, no frame in both), a frame of
///        another vertex count or other faces than its pair (or than the bind), caches of
///        different formats or point counts, other sample counts or frame numbers (with
///        `common`: no sample in both), a diagonal of zero length.
CompareResult compare_outputs(const std::string& a, const std::string& b,
                              const CompareOptions& options,
                              const std::function<void(const ComparedFrame&)>& frame_done = {});

}  // namespace skinslide
