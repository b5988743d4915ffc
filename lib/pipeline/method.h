// The one place where a run's method is chosen. Each method has the same shape in its own folder:
// its options, a per-patch bind-time set-up and a per-frame slide returning positions and a report
// (elastic/elastic_slide.h, paper/paper_slide.h), and what a run holds and tells of it: every
// patch's set-up, its figures for the report, its log text (elastic/elastic_method.h,
// paper/paper_method.h). Here they become one std::variant each (set-up, report, totals), visited
// in method.cpp alone: the rest of the pipeline (bind set-up, frames, report, log lines, dumps)
// asks these functions and never tests which method it runs.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/figures.h"
#include "core/types.h"
#include "elastic/elastic_method.h"
#include "mesh/patch.h"
#include "paper/paper_method.h"
#include "pipeline/options.h"
#include "slide/patch_slide.h"

namespace skinslide {

/// A run's method with its bind-time data: plain, immutable once built, shared by every frame.
using MethodSetup = std::variant<ElasticMethod, PaperMethod>;

/// What the method did to one patch in one frame.
using MethodReport = std::variant<ElasticReport, PaperReport>;

/// The method's sums over every patch of every frame (the report's "totals").
using MethodTotals = std::variant<ElasticTotals, PaperTotals>;

// ---- Bind time --------------------------------------------------------------------------------

/// The method `options` names, with `patch_count` empty patch slots.
MethodSetup method_setup(const SlideOptions& options, std::size_t patch_count);

/// The method's options.
SlideOptions method_options(const MethodSetup& method);

/// Sets patch `p` up for the method (not called for a skipped patch): fills its slot in
/// `method` and the patch's bind picture (Patch::bind_net, bind_net_flips).
/// Patches may be set up concurrently, each by one thread.
/// \param points bind positions of the patch's vertices (local ids)
/// \param weight slide weight per mesh vertex; empty = 1 everywhere
/// \param corners the corners chosen for it (the paper's method; ignored by the elastic one)
/// \param spare_thread the patch may use a second thread
void set_up_patch(MethodSetup& method, std::size_t p, Patch& patch, const Positions3& points,
                  const std::vector<double>& weight, const CornerChoice& corners,
                  bool spare_thread);

/// The square's corners of patch `p` as mesh vertex ids, and whether they were chosen; none for
/// the elastic method (its chart is a disk) or a skipped patch.
std::optional<SquareCorners> square_corners(const MethodSetup& method, std::size_t p,
                                            const Patch& patch);

// ---- Frames -----------------------------------------------------------------------------------

struct MethodSlide {
  PatchSlide slid;
  MethodReport report;
};

/// Slides patch `p` in one frame by the method (nothing moves in a skipped patch).
/// \param points the frame's positions of the patch's vertices (local ids)
/// \param id_image_size > 0: keep the frame's ID lookup image at that size
/// \throw Error(Numeric) naming the vertex when a slid position is not finite.
MethodSlide slide_patch(const MethodSetup& method, std::size_t p, const Patch& patch,
                        const Positions3& points, const std::vector<double>& weight,
                        int id_image_size);

// ---- What the method tells --------------------------------------------------------------------

/// For the bind's log line: "method elastic", "method paper, density inverse, holes fill".
std::string method_label(const MethodSetup& method);

/// The report's "options": the method's name and tunables.
Figures option_figures(const MethodSetup& method);

/// The report's entry for patch `p` at bind: its counts and loops, and what the method made of it.
Figures patch_figures(const MethodSetup& method, std::size_t p, const Patch& patch);

/// The method's figures of one patch in one frame (the report's frame entries, before the slide
/// figures both methods have).
Figures report_figures(const MethodReport& report);

/// The method's sums, none added yet.
MethodTotals method_totals(const MethodSetup& method);

/// Adds one patch's report of a frame to the sums.
void add_to_totals(MethodTotals& totals, const MethodReport& report);

/// The sums as the report's "totals" give them (between "moved" and "max_slide").
Figures total_figures(const MethodTotals& totals);

/// Patch p's report of one frame.
using MethodReportAt = std::function<const MethodReport&(std::size_t p)>;

/// A frame's log summary: the method's figures around `max_slide` (", max slide X").
/// \param report one per patch of `patches`
std::string frame_summary(const MethodSetup& method, const std::vector<Patch>& patches,
                          const MethodReportAt& report, const std::string& max_slide);

/// A patch's -v line in a frame, up to its slide figures ("elastic 12 it (converged), ...").
std::string patch_summary(const MethodSetup& method, std::size_t p, const MethodReport& report);

/// A patch found at rest after its slide (its frame is the bind to float32 precision: the slide
/// is dropped): the method's report says so too (elastic: stop "at rest", no energy gained,
/// no flips, no gain left, as for a frame the relaxation itself finds at rest).
void mark_at_rest(MethodReport& report);

/// Why a patch's slide in a frame did not converge ("small gain, first-order gain left 3.1%"),
/// empty when it did. The paper method's nets are solved exactly (or directly): always empty.
std::string convergence_fault(const MethodReport& report);

}  // namespace skinslide
