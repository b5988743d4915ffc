#include "pipeline/frame_window.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
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

// The file of `path`'s sequence numbered `number`, in `path`'s digits' width (arm.0100.obj for
// arm.0101.obj and 100); none when the number is negative.
std::optional<std::string> sequence_neighbour(const std::string& path, long long number) {
  const std::optional<std::string> sequence = frame_sequence(path);
  const std::optional<long long> own = frame_number(path);
  if (!sequence || !own || number < 0) return std::nullopt;
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string(), pattern = std::filesystem::path(*sequence).stem();
  const std::size_t width = stem.size() + 1 - pattern.size();  // the digits `#` stands for
  std::string digits = std::to_string(number);
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  std::string name = pattern;
  name.replace(name.find('#'), 1, digits);
  return (p.parent_path() / (name + p.extension().string())).string();
}

// The given FRAME files' first and last, when a file of their sequence lies beside either on
// disk: the warning, with the glob and --frames to pass instead.
std::optional<LogLine> cut_short_line(const WindowPlan& plan,
                                      const std::vector<std::size_t>& chosen,
                                      const std::vector<std::string>& paths,
                                      const std::string& frame_ranges) {
  const std::string& first = paths[plan.order.front()];
  const std::string& last = paths[plan.order.back()];
  std::error_code ec;
  const auto beside = [&](const std::string& path, long long step) -> std::optional<std::string> {
    const std::optional<std::string> n = sequence_neighbour(path, *frame_number(path) + step);
    if (n && std::filesystem::exists(*n, ec)) return n;
    return std::nullopt;
  };
  const std::optional<std::string> before = beside(first, -1), after = beside(last, +1);
  if (!before && !after) return std::nullopt;
  std::string where;
  if (before) where = "start at " + first + " with " + *before + " beside it";
  if (after)
    where += (before ? " and end at " : "end at ") + last + " with " + *after + " beside it";
  long long low = *frame_number(paths[chosen.front()]), high = low;
  for (std::size_t i : chosen) {
    low = std::min(low, *frame_number(paths[i]));
    high = std::max(high, *frame_number(paths[i]));
  }
  std::string glob = std::filesystem::path(first).parent_path().string();
  glob += (glob.empty() ? "" : "/") + *frame_sequence(first);
  glob.replace(glob.rfind('#'), 1, "*");
  const std::string ranges =
      frame_ranges.empty() ? std::to_string(low) + "-" + std::to_string(high) : frame_ranges;
  return LogLine{LogLevel::Warning,
                 "skinslide: warning: --window " + std::to_string(plan.reach) +
                     ": the frames given " + where +
                     ": the windows there are cut short where a run of the whole sequence has "
                     "neighbours, so these frames are not what that run writes. Give the whole "
                     "sequence and this chunk: --window " +
                     std::to_string(plan.reach) + " --frames " + ranges + " " + glob};
}

// Chosen frames short of the given ends: the frames beside them their windows relax.
std::optional<LogLine> chunk_line(const WindowPlan& plan, const std::vector<std::size_t>& chosen,
                                  const std::vector<std::string>& labels) {
  std::vector<char> is_chosen(plan.order.size(), 0);
  for (std::size_t i : chosen) is_chosen[i] = 1;
  std::vector<char> beside(plan.order.size(), 0);
  std::size_t first = chosen.front(), last = chosen.front();
  for (std::size_t i : chosen) {
    if (plan.place[i] < plan.place[first]) first = i;
    if (plan.place[i] > plan.place[last]) last = i;
    for (const WindowWeight& m : window_of(plan, i))
      if (!is_chosen[m.frame]) beside[m.frame] = 1;
  }
  const auto extra = static_cast<std::size_t>(std::count(beside.begin(), beside.end(), 1));
  if (extra == 0) return std::nullopt;
  return LogLine{
      LogLevel::Info,
      "skinslide: --window " + std::to_string(plan.reach) + ": " +
          (chosen.size() == 1 ? "the frame chosen, " + labels[first] + ", is"
                              : "the " + std::to_string(chosen.size()) + " frames chosen, " +
                                    labels[first] + " to " + labels[last] + ", are") +
          " a chunk of the " + std::to_string(plan.order.size()) +
          " given: " + std::to_string(extra) +
          " frames beside them are relaxed for their windows, not written, as one "
          "run of the whole sequence does (a farm task is given the whole sequence "
          "and its own --frames)"};
}

}  // namespace

std::optional<LogLine> window_ends_line(const WindowPlan& plan,
                                        const std::vector<std::size_t>& chosen,
                                        const std::vector<std::string>& labels,
                                        const std::vector<std::string>& paths,
                                        const std::string& frame_ranges) {
  if (plan.order.empty() || chosen.empty()) return std::nullopt;
  if (!paths.empty())
    if (std::optional<LogLine> line = cut_short_line(plan, chosen, paths, frame_ranges))
      return line;
  return chunk_line(plan, chosen, labels);
}

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
