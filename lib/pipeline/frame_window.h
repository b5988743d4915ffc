// --window N (README "Elastic"): each written frame's slide is the mean of its own and its
// neighbours' relaxations in the sequence, N on each side, weights N + 1 - |k| over their sum
// (one-sided within N of either end of the sequence). The sequence is the frames given (FRAME files
// in the order of their frame numbers, a cache's samples, a clip's), not the frames --frames
// chooses: a farm chunk given the whole sequence writes the bytes one run writes. Each frame is
// relaxed once, by whichever thread needs it first, and kept until every chosen frame whose window
// holds it is written.
#pragma once

#include <condition_variable>
#include <exception>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/log_lines.h"
#include "pipeline/slide_frame.h"

namespace skinslide {

/// The order of a run's frames and its reach N.
struct WindowPlan {
  int reach = 0;
  /// The windows wrap around the sequence's ends (--window-ends cycle); else one-sided there.
  bool cycle = false;
  std::vector<std::size_t> order;  ///< frame indices in sequence order
  std::vector<std::size_t> place;  ///< per frame index, its place in `order`
};

/// The plan of FRAME files (`paths`), ordered by their frame numbers (frame_ranges.h).
/// \throw Error(Usage) when a file has no frame number or two share one: the neighbours would
/// depend on the order the files are given in.
WindowPlan files_window_plan(int reach, const std::vector<std::string>& paths);

/// The plan of `count` frames in their own order (a cache's samples, a clip's).
WindowPlan ordered_window_plan(int reach, std::size_t count);

/// What a windowed run tells once about its ends (README "Farm"), before its frames:
///  - FRAME files (`paths`) given that stop short of their sequence on disk (the file numbered one
///    before the first given, or one after the last, is beside it): a Warning, the first and last
///    frames' windows cut short where a run of the whole sequence has neighbours, with what to pass
///    instead (the whole sequence as a glob, this chunk as --frames);
///  - else frames chosen (--frames) that start or end away from the ends of those given: an Info
///    line, the frames beside the chunk relaxed for its windows and not written, as one run does.
/// `labels` names each frame (a FRAME file, a cache's or clip's frame); `paths` is empty for a
/// cache or a clip (nothing beside them on disk). None when neither holds.
std::optional<LogLine> window_ends_line(const WindowPlan& plan,
                                        const std::vector<std::size_t>& chosen,
                                        const std::vector<std::string>& labels,
                                        const std::vector<std::string>& paths,
                                        const std::string& frame_ranges);

/// One frame of a window: a frame index and its weight (the weights of a window sum to 1).
struct WindowWeight {
  std::size_t frame = 0;
  double weight = 0;
};

/// Frame `frame`'s window, in sequence order from k = -N: the frames within N of it, weights
/// N + 1 - |k| over their sum: one-sided where the sequence ends, or with `cycle` wrapped around
/// them (a frame reached twice in a sequence shorter than the window counts once, its weights
/// summed).
std::vector<WindowWeight> window_of(const WindowPlan& plan, std::size_t frame);

/// The relaxations of a run's frames (relax_frame), each computed once, by the first thread that
/// asks (the others wait for it), and dropped once every chosen frame whose window holds it is
/// done. Thread-safe. A frame whose relaxation failed fails every window that holds it.
class RelaxationStore {
 public:
  using Relax = std::function<FrameRelaxations(std::size_t frame)>;
  RelaxationStore(WindowPlan plan, const std::vector<std::size_t>& chosen, Relax relax);

  /// Chosen frame `frame`'s window: its frames' relaxations, each with its weight; a frame whose
  /// relaxation failed has its error instead.
  struct Member {
    std::shared_ptr<const FrameRelaxations> relaxations;
    std::exception_ptr error;
    std::size_t frame = 0;
    double weight = 0;
  };
  std::vector<Member> window(std::size_t frame);

  /// Chosen frame `frame` is done (written or failed): its window's frames lose one use each.
  void done(std::size_t frame);

 private:
  struct Entry {
    std::shared_ptr<const FrameRelaxations> value;
    std::exception_ptr error;
    bool ready = false;
    bool running = false;
    int uses = 0;
  };
  // The frame's relaxation, computed here if no thread has started it; null and `error` set
  // when it failed.
  std::shared_ptr<const FrameRelaxations> get(std::size_t frame, std::exception_ptr& error);

  const WindowPlan plan_;
  const Relax relax_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::map<std::size_t, Entry> entries_;
};

/// Rethrows the first error of frame `frame`'s window, if any: the frame's own as it is (it fails
/// as it would alone), else a neighbour's as "LABEL: its --window neighbour ERROR" (`label` names
/// the frame): the window's mean without it would be another one.
void rethrow_window_error(const std::vector<RelaxationStore::Member>& window, std::size_t frame,
                          const std::string& label);

/// The window's mean of chart points, patch by patch (window_mean.h chart_point_mean), and the
/// chosen frame's own relaxations: what slide_frame writes. `own` is the member whose frame is
/// `frame`. \pre no member has an error.
WindowedFrame windowed_frame(const std::vector<RelaxationStore::Member>& window, std::size_t frame);

}  // namespace skinslide
