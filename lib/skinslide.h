// skinslide as a library: what a program embedding it includes (the command line in cli/ and
// the Python module in lib/python/ are its two clients). Arrays in and out (set_up, slide,
// slide_sequence with a window over the neighbouring frames, below); or a whole run of files, as
// the command line makes it (run(), pipeline/run.h), with point caches' farm chunks joined by
// join_cache_chunks (io/cache_chunks.h) and the temporaries of a cancelled run removed
// (remove_temporaries_on_termination, io/atomic_write.h).
//
//   skinslide::Bind bind{positions, face_vertices, face_sizes};     // arrays, 0-based ids
//   const skinslide::BindSetup setup = skinslide::set_up(bind, {patch_faces}, PaperOptions{});
//   std::vector<double> out(positions.size());
//   const auto report = skinslide::slide(setup, frame_positions, out);  // any thread
//
// The set-up is built once and never changes: frames may be slid from several threads at once,
// and a frame's result depends on (set-up, frame) only, never on the thread count. Errors are
// skinslide::Error (core/error.h), whose kind says what was wrong: Usage (an option or a
// control out of range, an id past the last vertex), Input (the arrays: sizes, face ids,
// topology), Numeric (a solve failed), Internal (a bug).
#pragma once

#include <span>
#include <vector>

#include "core/error.h"
#include "core/types.h"
#include "io/atomic_write.h"
#include "io/cache_chunks.h"
#include "pipeline/bind_setup.h"
#include "pipeline/method.h"
#include "pipeline/options.h"
#include "pipeline/run.h"
#include "pipeline/run_options.h"
#include "pipeline/slide_frame.h"

namespace skinslide {

/// A mesh as arrays, viewed, not copied: positions #V x 3 (x y z per vertex, row after row);
/// faces as their vertex ids one face after another, with each face's corner count in
/// `face_sizes` (empty: every face a triangle). Faces in the order patch face ids count them.
struct Bind {
  std::span<const double> positions;
  std::span<const Index> face_vertices;
  std::span<const Index> face_sizes;
};

/// Builds the bind set-up: patches (each entry a selection of face ids; each is split into its
/// edge-connected patches), the method and its options, the controls (slide weights #V, pins,
/// strength, corners, outer loops; SlideControls).
/// \param threads patches set up at once; the set-up is the same for any count
/// \throw Error(Usage) for an option out of its range (the command line's ranges, README
///        "Options") or a bad control; Error(Input) for arrays of the wrong size, a face id
///        past the last face or vertex, a face of fewer than 3 corners, and the topology errors
///        of bind_setup; Error(Numeric) when a bind net cannot be solved.
BindSetup set_up(const Bind& bind, const std::vector<std::vector<Index>>& patches,
                 const SlideOptions& options = {}, const SlideControls& controls = {},
                 unsigned threads = 1);

/// Checks a method's options against the ranges of its option table (core/option.h), which the
/// command line checks too.
/// \throw Error(Usage) naming the option, its value and its range.
void check_options(const SlideOptions& options);

/// Slides one frame: `frame` holds the deformed positions (#V x 3, the bind's vertex order);
/// `out` (#V x 3) receives the frame with every slid vertex moved. Returns what happened to each
/// patch (frame_figures names its figures; the edge-length spreads only with `edge_spread`,
/// which costs more: tests/bench/README.md "Performance"). Pure and thread-safe.
/// \throw Error(Input) when `frame` or `out` is not #V x 3; Error(Numeric) when a slide fails.
std::vector<PatchFrameReport> slide(const BindSetup& setup, std::span<const double> frame,
                                    std::span<double> out, bool edge_spread = false);

/// Slides a sequence of frames: frames[k] (#V x 3 each) is the sequence's k-th frame, outs[k]
/// receives it slid. With `window` N > 0 (the elastic method's --window, README "Slow motion";
/// lib/elastic/README.md rule 12) each frame is written at the mean of its own and its N
/// neighbours' relaxations on each side, one-sided where the sequence ends: the bits the command
/// line writes for the same frames in the same order; with `ends` Cycle the sequence is a loop and
/// the windows wrap around its ends (--window-ends cycle). With 0 each frame is slide()'s. Frames
/// are relaxed and written on `threads` threads (each relaxed once, kept while a window needs it);
/// the result is the same for any count. Returns each frame's reports, as slide().
/// \throw Error(Usage) for a window out of [0, kMaxWindow], a window with the paper method, or
///        Cycle ends without a window;
///        Error(Input) as slide(), naming the frame; Error(Numeric) naming the frame that failed
///        (the first in the sequence), or the neighbour whose relaxation a window needed.
std::vector<std::vector<PatchFrameReport>> slide_sequence(
    const BindSetup& setup, std::span<const std::span<const double>> frames,
    std::span<const std::span<double>> outs, int window, bool edge_spread = false,
    unsigned threads = 1, WindowEnds ends = WindowEnds::OneSided);

}  // namespace skinslide
