#include "pipeline/method.h"

#include <memory>
#include <utility>

namespace skinslide {
namespace {

// One lambda a method: std::visit's overload set.
template <class... F>
struct Each : F... {
  using F::operator()...;
};
// Spelled out: clang before 17 deduces no aggregate's template arguments (the fuzz build).
template <class... F>
Each(F...) -> Each<F...>;

}  // namespace

MethodSetup method_setup(const SlideOptions& options, std::size_t patch_count) {
  return std::visit(
      Each{[&](const ElasticOptions& o) -> MethodSetup {
             return ElasticMethod{o, std::vector<std::shared_ptr<const ElasticSetup>>(patch_count)};
           },
           [&](const PaperOptions& o) -> MethodSetup {
             return PaperMethod{o, std::vector<PaperSetup>(patch_count)};
           }},
      options);
}

SlideOptions method_options(const MethodSetup& method) {
  return std::visit([](const auto& m) -> SlideOptions { return m.options; }, method);
}

void set_up_patch(MethodSetup& method, std::size_t p, Patch& patch, const Positions3& points,
                  const std::vector<double>& weight, const CornerChoice& corners,
                  bool spare_thread) {
  std::visit(
      Each{[&](ElasticMethod& m) { set_up_patch(m, p, patch, points, weight); },
           [&](PaperMethod& m) { set_up_patch(m, p, patch, points, corners, spare_thread); }},
      method);
}

std::optional<SquareCorners> square_corners(const MethodSetup& method, std::size_t p,
                                            const Patch& patch) {
  return std::visit(
      Each{[](const ElasticMethod&) -> std::optional<SquareCorners> { return std::nullopt; },
           [&](const PaperMethod& m) { return square_corners(m, p, patch); }},
      method);
}

MethodSlide slide_patch(const MethodSetup& method, std::size_t p, const Patch& patch,
                        const Positions3& points, const std::vector<double>& weight,
                        int id_image_size) {
  return std::visit(
      [&](const auto& m) {
        auto s = slide_patch(m, p, patch, points, weight, id_image_size);
        return MethodSlide{std::move(s.slid), std::move(s.report)};
      },
      method);
}

std::string method_label(const MethodSetup& method) {
  return std::visit([](const auto& m) { return method_label(m); }, method);
}

Figures option_figures(const MethodSetup& method) {
  return std::visit(
      [](const auto& m) {
        Figures f{{"method", method_name(m.options)}};
        using Options = std::decay_t<decltype(m.options)>;
        for (Figure& o : option_figures(option_table<Options>(), m.options))
          f.push_back(std::move(o));
        return f;
      },
      method);
}

Figures patch_figures(const MethodSetup& method, std::size_t p, const Patch& patch) {
  return std::visit([&](const auto& m) { return patch_figures(m, p, patch); }, method);
}

Figures report_figures(const MethodReport& report) {
  return std::visit([](const auto& r) { return report_figures(r); }, report);
}

MethodTotals method_totals(const MethodSetup& method) {
  return std::visit(Each{[](const ElasticMethod&) -> MethodTotals { return ElasticTotals{}; },
                         [](const PaperMethod&) -> MethodTotals { return PaperTotals{}; }},
                    method);
}

void add_to_totals(MethodTotals& totals, const MethodReport& report) {
  std::visit(Each{[&](ElasticTotals& t) { t.add(std::get<ElasticReport>(report)); },
                  [&](PaperTotals& t) { t.add(std::get<PaperReport>(report)); }},
             totals);
}

Figures total_figures(const MethodTotals& totals) {
  return std::visit([](const auto& t) { return t.figures(); }, totals);
}

std::string frame_summary(const MethodSetup& method, const std::vector<Patch>& patches,
                          const MethodReportAt& report, const std::string& max_slide) {
  return std::visit(Each{[&](const ElasticMethod&) {
                           return frame_summary(
                               patches,
                               [&](std::size_t p) -> const ElasticReport& {
                                 return std::get<ElasticReport>(report(p));
                               },
                               max_slide);
                         },
                         [&](const PaperMethod& m) {
                           return frame_summary(
                               m, patches,
                               [&](std::size_t p) -> const PaperReport& {
                                 return std::get<PaperReport>(report(p));
                               },
                               max_slide);
                         }},
                    method);
}

void mark_at_rest(MethodReport& report) {
  // The figures describe what is written: the frame itself (the work done stays counted).
  if (auto* elastic = std::get_if<ElasticReport>(&report)) {
    elastic->stop = stop_name(ElasticStop::AtRest);
    elastic->energy_after = elastic->energy_before;
    elastic->slid_flips = 0;
    elastic->gain_left = 0;
  }
  if (auto* paper = std::get_if<PaperReport>(&report)) paper->slid_flips = 0;
}

std::string convergence_fault(const MethodReport& report) {
  const auto* elastic = std::get_if<ElasticReport>(&report);
  return elastic && !converged(*elastic) ? convergence_text(*elastic) : std::string();
}

std::string patch_summary(const MethodSetup& method, std::size_t p, const MethodReport& report) {
  return std::visit(
      Each{
          [&](const ElasticMethod&) { return patch_summary(std::get<ElasticReport>(report)); },
          [&](const PaperMethod& m) { return patch_summary(m, p, std::get<PaperReport>(report)); }},
      method);
}

}  // namespace skinslide
