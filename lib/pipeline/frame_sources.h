// Where a run's frames come from and how each becomes its output (README "Usage", "glTF", "Point
// caches"): a FRAME file read, a rigged character posed at one time of its clip (--animation), or
// a point cache's sample; slid (pipeline/slide_frame.h), its dumps and previews written, then its
// slid file or its sample of the output cache. Each frame is a pure function of its input.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/mesh_file.h"
#include "io/point_cache.h"
#include "pipeline/bind_setup.h"
#include "pipeline/cache_frames.h"
#include "pipeline/frame_plans.h"
#include "pipeline/log_lines.h"
#include "pipeline/report.h"
#include "pipeline/rig_frames.h"
#include "pipeline/run_options.h"

namespace skinslide {

/// A run's frames besides FRAME files (a rigged character's clip or a point cache's samples), and
/// where every frame goes.
struct FrameSource {
  FramePlan plan;
  RigClip clip;       ///< --animation
  CacheFrames cache;  ///< a point cache FRAME
};

/// The plan of FRAME files is made before the bind is read (`files`); a clip's and a cache's once
/// the character or the cache's header is: with --animation, BIND is a rigged glTF character whose
/// frames are its skin posed at the clip's sampled times (pipeline/rig_frames.h); a cache's frames
/// are its samples (pipeline/cache_frames.h).
/// \throw Error as rig_clip, open_cache_frames and the plans.
FrameSource frame_source(const RunOptions& o, const MeshFile& bind, FramePlan files,
                         bool cache_run);

/// The header of the cache a run writes (FramePlan::cache): the chosen samples of the FRAME
/// cache, of the clip, or of the FRAME files (FramePlan::whole).
CacheHeader output_cache_header(const RunOptions& o, const MeshFile& bind,
                                const FrameSource& source);

/// Frame i of the run as its errors name it.
const std::string& frame_label(const RunOptions& o, const FrameSource& source, std::size_t i);

/// Where a frame goes in the point cache a run writes (FramePlan::cache): the cache's writer and
/// the frame's sample in it. No writer: the frame has a file of its own.
struct CacheSlot {
  CacheWriter* writer = nullptr;
  std::size_t sample = 0;
};

/// What became of one frame: its log lines, whether every patch's slide converged, and whether
/// its window cost it much energy.
struct FrameOutcome {
  std::vector<LogLine> lines;
  bool converged = true;
  bool window_costly = false;  ///< its --window mean costs ten points of energy (log_lines.h)
};

/// Frame i of the run: read (or posed), slid and written. With `record`, the report's record of
/// it. \throw Error naming the frame; nothing of it is written then. With --require-converged a
/// patch that did not converge is such an error (Numeric), naming the patch and its stop.
/// With `window` (--window), each patch is written at the window's mean (slide_frame).
FrameOutcome run_source_frame(const BindSetup& setup, const MeshFile& bind,
                              const FrameSource& source, const RunOptions& o, std::size_t i,
                              CacheSlot slot, ReportFrame* record,
                              const WindowedFrame* window = nullptr);

/// Frame i of the run relaxed (relax_frame), for the windows that hold it: read (or posed) as
/// run_source_frame reads it. \throw Error naming the frame.
FrameRelaxations relax_source_frame(const BindSetup& setup, const MeshFile& bind,
                                    const FrameSource& source, const RunOptions& o, std::size_t i);

}  // namespace skinslide
