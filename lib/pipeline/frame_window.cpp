#include "pipeline/frame_window.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <utility>

#include "core/check.h"
#include "core/error.h"
#include "elastic/window_mean.h"
#include "pipeline/frame_ranges.h"

namespace skinslide {
namespace {

WindowPlan plan_in_order(int reach, std::vector<std::size_t> order) {
  WindowPlan plan;
  plan.reach = reach;
  plan.place.assign(order.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) plan.place[order[k]] = k;
  plan.order = std::move(order);
  return plan;
}

}  // namespace

WindowPlan files_window_plan(int reach, const std::vector<std::string>& paths) {
  std::vector<long long> number(paths.size());
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::optional<long long> n = frame_number(paths[i]);
    if (!n)
      throw Error(ErrorKind::Usage, "--window " + std::to_string(reach) + ": " + paths[i] +
                                        " has no frame number (name.0042.obj), and a window "
                                        "takes each frame's neighbours by their numbers");
    number[i] = *n;
  }
  std::vector<std::size_t> order(paths.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return number[a] < number[b]; });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (number[order[k]] == number[order[k - 1]])
      throw Error(ErrorKind::Usage,
                  "--window " + std::to_string(reach) + ": " + paths[order[k - 1]] + " and " +
                      paths[order[k]] + " are both frame " + std::to_string(number[order[k]]) +
                      ": a window takes each frame's neighbours by their numbers");
  return plan_in_order(reach, std::move(order));
}

WindowPlan ordered_window_plan(int reach, std::size_t count) {
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  return plan_in_order(reach, std::move(order));
}

std::vector<WindowWeight> window_of(const WindowPlan& plan, std::size_t frame) {
  const long long at = static_cast<long long>(plan.place[frame]);
  const long long n = static_cast<long long>(plan.order.size());
  // One-sided at the ends of the sequence: narrowed to stay symmetric, it would hand the first
  // and last frames their own jumps back (the first frame's window would be itself alone). A
  // loop's seam is smoothed only when the sequence is said to be one (cycle).
  std::vector<WindowWeight> out;
  double sum = 0;
  for (long long k = -plan.reach; k <= plan.reach; ++k) {
    long long place = at + k;
    if (plan.cycle)
      place = ((place % n) + n) % n;
    else if (place < 0 || place >= n)
      continue;
    const std::size_t f = plan.order[static_cast<std::size_t>(place)];
    const double w = static_cast<double>(plan.reach + 1 - std::llabs(k));
    sum += w;
    const auto same =
        std::find_if(out.begin(), out.end(), [&](const WindowWeight& m) { return m.frame == f; });
    if (same != out.end())
      same->weight += w;
    else
      out.push_back({f, w});
  }
  for (WindowWeight& m : out) m.weight /= sum;
  return out;
}

RelaxationStore::RelaxationStore(WindowPlan plan, const std::vector<std::size_t>& chosen,
                                 Relax relax)
    : plan_(std::move(plan)), relax_(std::move(relax)) {
  for (std::size_t f : chosen)
    for (const WindowWeight& m : window_of(plan_, f)) ++entries_[m.frame].uses;
}

std::shared_ptr<const FrameRelaxations> RelaxationStore::get(std::size_t frame,
                                                             std::exception_ptr& error) {
  std::unique_lock lock(mutex_);
  Entry& e = entries_.at(frame);
  if (!e.ready && !e.running) {
    e.running = true;
    lock.unlock();
    std::shared_ptr<const FrameRelaxations> value;
    std::exception_ptr failed;
    try {
      value = std::make_shared<const FrameRelaxations>(relax_(frame));
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    e.value = std::move(value);
    e.error = failed;
    e.ready = true;
    e.running = false;
    ready_.notify_all();
  }
  ready_.wait(lock, [&] { return e.ready; });
  error = e.error;
  return e.value;
}

std::vector<RelaxationStore::Member> RelaxationStore::window(std::size_t frame) {
  std::vector<Member> out;
  for (const WindowWeight& m : window_of(plan_, frame)) {
    Member member{nullptr, nullptr, m.frame, m.weight};
    member.relaxations = get(m.frame, member.error);
    out.push_back(std::move(member));
  }
  return out;
}

void RelaxationStore::done(std::size_t frame) {
  std::lock_guard lock(mutex_);
  for (const WindowWeight& m : window_of(plan_, frame)) {
    auto it = entries_.find(m.frame);
    if (it != entries_.end() && --it->second.uses == 0 && it->second.ready) entries_.erase(it);
  }
}

void rethrow_window_error(const std::vector<RelaxationStore::Member>& window, std::size_t frame,
                          const std::string& label) {
  for (const RelaxationStore::Member& m : window)
    if (m.error && m.frame == frame) std::rethrow_exception(m.error);
  for (const RelaxationStore::Member& m : window)
    if (m.error) try {
        std::rethrow_exception(m.error);
      } catch (const Error& e) {
        throw Error(e.kind(), label + ": its --window neighbour " + e.what());
      }
}

WindowedFrame windowed_frame(const std::vector<RelaxationStore::Member>& window,
                             std::size_t frame) {
  WindowedFrame out;
  for (const RelaxationStore::Member& m : window) {
    SKINSLIDE_CHECK(m.relaxations != nullptr, "a window's frames are relaxed");
    if (m.frame == frame) out.own = m.relaxations.get();
  }
  SKINSLIDE_CHECK(out.own != nullptr, "a window holds its own frame");
  const std::size_t patches = out.own->patches.size();
  out.mean.resize(patches);
  for (std::size_t p = 0; p < patches; ++p) {
    if (out.own->patches[p].uv.empty()) continue;
    std::vector<WindowFrame> frames;
    for (const RelaxationStore::Member& m : window)
      frames.push_back({&m.relaxations->patches[p].uv, m.weight});
    out.mean[p] = chart_point_mean(frames);
  }
  return out;
}

}  // namespace skinslide
