#include "elastic/relax.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/check.h"
#include "core/error.h"
#include "elastic/step_system.h"

namespace skinslide {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// A triangle's three gradient rows G_k (J = sum_k x_k G_k^T) from its rest inverse D.
std::array<Vec2, 3> gradient_rows(const Eigen::Matrix2d& D) {
  const Vec2 g1 = D.row(0).transpose(), g2 = D.row(1).transpose();
  return {-(g1 + g2), g1, g2};
}

// The 2D inverse of a bind triangle's edges in a frame of its plane; zero without area.
Eigen::Matrix2d rest_inverse(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 f1 = b - a, f2 = c - a;
  const double l1 = f1.norm();
  const double twice_area = f1.cross(f2).norm();
  // Below this the triangle's shape is round-off: it has no rest shape to return to.
  const double scale = f1.squaredNorm() + f2.squaredNorm() + (f2 - f1).squaredNorm();
  if (!(l1 > 0) || !(twice_area > 1e-12 * scale)) return Eigen::Matrix2d::Zero();
  const Vec3 ex = f1 / l1;
  const double x2 = f2.dot(ex);
  const double y2 = twice_area / l1;
  Eigen::Matrix2d B;
  B << l1, x2, 0, y2;
  return B.inverse();
}

bool has_rest_shape(const Eigen::Matrix2d& D) { return D(0, 0) != 0; }

Mat32 deformation_gradient(const Positions3& x, const Triangle& t, const Eigen::Matrix2d& D) {
  Mat32 e;
  e.col(0) = x[t[1]] - x[t[0]];
  e.col(1) = x[t[2]] - x[t[0]];
  return e * D;
}

// The rotation nearest J (3x2, orthonormal columns: ARAP's local step) and the ARAP energy
// (s1 - s)^2 + (s2 - s)^2 of J's singular values, which is |J - s R|^2 for that R.
struct RotationFit {
  double energy = 0;
  Mat32 rotation = Mat32::Zero();
};

RotationFit fit_rotation(const Mat32& J, double s, const Vec3& frame_normal) {
  RotationFit out;
  const double a = J.col(0).squaredNorm(), b = J.col(0).dot(J.col(1)), c = J.col(1).squaredNorm();
  const double tr = a + c;
  // The eigenvalues of J^T J, each to round-off: the energy of a frame at rest is then round-off
  // squared, not round-off.
  const double half_gap = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double l1 = 0.5 * tr + half_gap;
  const double det = std::max(a * c - b * b, 0.0);
  const double l2 = l1 > 0 ? det / l1 : 0.0;
  const double s1 = std::sqrt(l1), s2 = std::sqrt(l2);
  out.energy = (s1 - s) * (s1 - s) + (s2 - s) * (s2 - s);
  if (!(tr > 0)) return out;
  // R = U V^T from J's singular vectors; with J of rank one, U's second column lies in the
  // frame's tangent plane.
  Vec2 v1 = std::abs(b) > 0 ? Vec2(b, l1 - a) : (a >= c ? Vec2(1, 0) : Vec2(0, 1));
  v1.normalize();
  const Vec2 v2(-v1.y(), v1.x());
  const Vec3 u1 = J * v1 / s1;
  Vec3 u2 = Vec3::Zero();
  if (s2 > 1e-12 * s1) {
    u2 = J * v2 / s2;
  } else if (const double nn = frame_normal.norm(); nn > 0) {
    u2 = frame_normal.cross(u1) / nn;
  }
  out.rotation = u1 * v1.transpose() + u2 * v2.transpose();
  return out;
}

// The ARAP energy of the patch at x: w sum_t min_R |J_t - s R|^2.
double arap_energy(const ElasticSetup& setup, const Positions3& x, double s,
                   const std::vector<Vec3>& frame_normals) {
  const auto& tris = setup.chart.triangles;
  double total = 0;
  for (Index t = 0; t < setup.chart.patch_triangle_count; ++t) {
    const Eigen::Matrix2d& D = setup.rest_inverse[t];
    if (has_rest_shape(D))
      total += fit_rotation(deformation_gradient(x, tris[t], D), s, frame_normals[t]).energy;
  }
  return setup.triangle_weight * total;
}

// ARAP's local step: every triangle's nearest rotation at x.
std::vector<Mat32> fitted_rotations(const ElasticSetup& setup, const Positions3& x,
                                    const std::vector<Vec3>& frame_normals) {
  const auto& tris = setup.chart.triangles;
  std::vector<Mat32> R(setup.chart.patch_triangle_count, Mat32::Zero());
  for (Index t = 0; t < setup.chart.patch_triangle_count; ++t) {
    const Eigen::Matrix2d& D = setup.rest_inverse[t];
    if (has_rest_shape(D))
      R[t] = fit_rotation(deformation_gradient(x, tris[t], D), 1.0, frame_normals[t]).rotation;
  }
  return R;
}

// ARAP's global energy with the rotations held, w sum_t |J_t - s R_t|^2, and optionally its
// gradient per local vertex.
double held_rotation_energy(const ElasticSetup& setup, const Positions3& x, double s,
                            const std::vector<Mat32>& R, Positions3* gradient) {
  const auto& tris = setup.chart.triangles;
  if (gradient) gradient->assign(x.size(), Vec3::Zero());
  double total = 0;
  for (Index t = 0; t < setup.chart.patch_triangle_count; ++t) {
    const Eigen::Matrix2d& D = setup.rest_inverse[t];
    if (!has_rest_shape(D)) continue;
    const Mat32 r = deformation_gradient(x, tris[t], D) - s * R[t];
    total += r.squaredNorm();
    if (!gradient) continue;
    const std::array<Vec2, 3> G = gradient_rows(D);
    for (int k = 0; k < 3; ++k) (*gradient)[tris[t][k]] += 2 * setup.triangle_weight * (r * G[k]);
  }
  return setup.triangle_weight * total;
}

// The frame's surface over a chart triangle: dPhi/du, 3x2.
Mat32 chart_jacobian(const ElasticSetup& setup, const Positions3& frame, Index t) {
  const Triangle& tri = setup.chart.triangles[t];
  Mat32 e;
  e.col(0) = frame[tri[1]] - frame[tri[0]];
  e.col(1) = frame[tri[2]] - frame[tri[0]];
  return e * setup.chart.inverse_edges[t];
}

Vec3 surface_point(const Positions3& frame, const Triangle& tri, const ChartPoint& p) {
  return p.weight[0] * frame[tri[0]] + p.weight[1] * frame[tri[1]] + p.weight[2] * frame[tri[2]];
}

// At a chart vertex Phi has no Jacobian: the least-squares linear map from the vertex's chart
// one-ring to its frame one-ring, projected on the frame's tangent plane there (edges weighted by
// 1 / |chart edge|^2). A model only: the line search measures the true energy.
Mat32 vertex_jacobian(const ElasticSetup& setup, const Positions3& frame,
                      const std::vector<Vec3>& frame_normals, Index v) {
  const Chart& chart = setup.chart;
  Vec3 n = Vec3::Zero();
  for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k)
    n += frame_normals[chart.corner_triangles[k]];
  const double nn = n.norm();
  if (nn > 0) n /= nn;
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Mat32 B = Mat32::Zero();
  for (Index k = chart.corner_start[v]; k < chart.corner_start[v + 1]; ++k)
    for (Index r : chart.triangles[chart.corner_triangles[k]]) {
      if (r == v) continue;
      const Vec2 du = chart.uv[r] - chart.uv[v];
      Vec3 dx = frame[r] - frame[v];
      dx -= dx.dot(n) * n;
      const double w = 1.0 / std::max(du.squaredNorm(), 1e-300);
      A += w * du * du.transpose();
      B += w * dx * du.transpose();
    }
  const double det = A.determinant();
  if (!(std::abs(det) > 0) || !std::isfinite(det)) return Mat32::Zero();
  return B * A.inverse();
}

// How far direction d (non-zero) points into the wedge of patch triangle t at its corner v: the
// smaller of the two normalised crosses with the wedge's edges, >= 0 inside.
double wedge_score(const Chart& chart, Index t, Index v, const Vec2& d) {
  const Triangle& tri = chart.triangles[t];
  const int c = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
  const Vec2 a = chart.uv[tri[(c + 1) % 3]] - chart.uv[v];
  const Vec2 b = chart.uv[tri[(c + 2) % 3]] - chart.uv[v];
  return std::min(cross2(a, d) / (a.norm() * d.norm()), cross2(d, b) / (b.norm() * d.norm()));
}

// The patch triangle a point enters when it leaves `u` along `d`: at a chart vertex the incident
// triangle whose wedge holds d; on an edge the triangle across it when d points out; else its own.
Index entered_triangle(const Chart& chart, Index vertex_at, const Vec2& u, Index t, const Vec2& d) {
  if (d.x() == 0 && d.y() == 0) return t;
  if (vertex_at >= 0) {
    Index best = t;
    double best_score = -INFINITY;
    for (Index k = chart.corner_start[vertex_at]; k < chart.corner_start[vertex_at + 1]; ++k) {
      const Index s = chart.corner_triangles[k];
      const double score = wedge_score(chart, s, vertex_at, d);
      if (score > best_score) {
        best_score = score;
        best = s;
      }
    }
    return best;
  }
  const std::array<double, 3> w = chart_barycentric(chart, t, u);
  const Vec2 dm = chart.inverse_edges[t] * d;
  const std::array<double, 3> dw{-dm.x() - dm.y(), dm.x(), dm.y()};
  Index out = t;
  double steepest = 0;
  for (int k = 0; k < 3; ++k)
    if (w[k] <= 1e-12 && dw[k] < steepest) {
      const Index nb = chart.neighbour[t][k];
      if (nb >= 0 && nb < chart.patch_triangle_count) {
        out = nb;
        steepest = dw[k];
      }
    }
  return out;
}

// The largest step along d before a chart triangle with a moving corner loses its area: the
// smallest positive root of its signed area, a quadratic in the step (Smith & Schaefer 2015).
double max_step(const ElasticSetup& setup, const Positions2& node_uv, const Positions2& node_d,
                std::vector<double>* roots) {
  const Chart& chart = setup.chart;
  double alpha = INFINITY;
  if (roots) roots->assign(chart.patch_triangle_count, INFINITY);
  for (Index t = 0; t < chart.patch_triangle_count; ++t) {
    const Triangle& tri = chart.triangles[t];
    const Vec2 d0 = node_d[tri[0]], d1 = node_d[tri[1]] - d0, d2 = node_d[tri[2]] - d0;
    if (d1.isZero(0) && d2.isZero(0)) continue;
    const Vec2 e1 = node_uv[tri[1]] - node_uv[tri[0]], e2 = node_uv[tri[2]] - node_uv[tri[0]];
    const double a = cross2(d1, d2);
    const double b = cross2(e1, d2) + cross2(d1, e2);
    const double c = cross2(e1, e2);
    double root = INFINITY;
    if (std::abs(a) <= 1e-14 * (std::abs(b) + std::abs(c))) {
      if (b < 0) root = -c / b;
    } else {
      const double disc = b * b - 4 * a * c;
      if (disc >= 0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        for (const double r : {q / a, q != 0 ? c / q : INFINITY})
          if (r > 0) root = std::min(root, r);
      }
    }
    alpha = std::min(alpha, root);
    if (roots) (*roots)[t] = root;
  }
  return alpha;
}

// One patch's relaxation in one frame: the frame, the slid patch so far, and the steps that
// move it (README rules 6-10). The rounds are driven by relax_patch.
class Relaxation {
 public:
  Relaxation(const ElasticSetup& setup, const Positions3& frame,
             const std::vector<Vec3>& frame_normals, double scale, ElasticResult& result)
      : setup_(setup),
        chart_(setup.chart),
        tris_(setup.chart.triangles),
        nt_(setup.chart.patch_triangle_count),
        m_(static_cast<Index>(setup.movable.size())),
        frame_(frame),
        normals_(frame_normals),
        s_(scale),
        result_(result),
        x_(frame),
        node_uv_(setup.chart.uv),
        jacobian_(nt_),
        on_vertex_(m_, 1),
        T_(m_),
        held_(m_),
        switched_(m_),
        hold_cap_(std::max<Index>(16, m_ / 10)),
        system_(setup.metric_start, setup.metric_column, setup.metric_value, *setup.step_multigrid),
        g_movable_(m_) {
    for (Index t = 0; t < nt_; ++t) jacobian_[t] = chart_jacobian(setup, frame, t);
  }

  const Positions3& positions() const { return x_; }

  // ARAP's local step: the rotations nearest the slid patch, held from here on.
  void fit_rotations() {
    R_ = fitted_rotations(setup_, x_, normals_);
    E_ = held_rotation_energy(setup_, x_, s_, R_, &g_);
  }
  double energy() const { return E_; }

  // One Gauss-Newton step in the chart, made a descent and fold-free; false when no step lowers
  // the energy.
  bool step() {
    for (Index i = 0; i < m_; ++i)
      T_[i] = on_vertex_[i] ? vertex_jacobian(setup_, frame_, normals_, setup_.movable[i])
                            : jacobian_[result_.where[i].triangle];
    std::fill(held_.begin(), held_.end(), 0);
    std::fill(switched_.begin(), switched_.end(), 0);
    std::vector<Direction> candidates = steps_with_holds(model_step());
    for (Direction& c : candidates) descend(c);
    result_.held += static_cast<int>(std::count(held_.begin(), held_.end(), 1));
    Trial best;
    double E_new = E_;
    if (!line_search(candidates, best, E_new)) return false;
    for (Index i = 0; i < m_; ++i) {
      if (best.uv[i] == result_.uv[i]) continue;
      result_.uv[i] = best.uv[i];
      result_.where[i] = best.where[i];
      node_uv_[setup_.movable[i]] = best.uv[i];
      on_vertex_[i] = 0;
    }
    x_ = std::move(best.x);
    E_ = held_rotation_energy(setup_, x_, s_, R_, &g_);
    return true;
  }

 private:
  // A step direction and its true first-order change: each vertex moves with the Jacobian of
  // the triangle it enters.
  struct Direction {
    Positions2 d;
    std::vector<Index> entered;
    std::vector<Mat32> T_true;
    double slope = 0;  // true
    double model = 0;  // with the model's Jacobians
  };
  // Where a step puts the movable vertices, in the chart and on the frame.
  struct Trial {
    Positions2 uv;
    std::vector<ChartPoint> where;
    Positions3 x;
  };

  Direction direction(Positions2 d) const {
    Direction out;
    out.d = std::move(d);
    out.entered.resize(m_);
    out.T_true.resize(m_);
    for (Index i = 0; i < m_; ++i) {
      const Index v = setup_.movable[i];
      out.entered[i] = entered_triangle(chart_, on_vertex_[i] ? v : -1, result_.uv[i],
                                        result_.where[i].triangle, out.d[i]);
      out.T_true[i] = jacobian_[out.entered[i]];
      out.model += g_[v].dot(T_[i] * out.d[i]);
      out.slope += g_[v].dot(out.T_true[i] * out.d[i]);
    }
    return out;
  }

  Trial trial(const Direction& dir, double alpha) const {
    Trial t{result_.uv, result_.where, x_};
    for (Index i = 0; i < m_; ++i) {
      if (dir.d[i].isZero(0)) continue;
      const Index v = setup_.movable[i];
      t.uv[i] = result_.uv[i] + alpha * dir.d[i];
      t.where[i] = locate_in_chart(chart_, t.uv[i], dir.entered[i]);
      t.x[v] = surface_point(frame_, tris_[t.where[i].triangle], t.where[i]);
    }
    return t;
  }

  // The patch triangles with a corner that `dir` moves, ascending: only they can turn.
  std::vector<Index> moving_triangles(const Direction& dir) const {
    std::vector<char> moves(nt_, 0);
    for (Index i = 0; i < m_; ++i) {
      if (dir.d[i].isZero(0)) continue;
      const Index v = setup_.movable[i];
      for (Index k = chart_.corner_start[v]; k < chart_.corner_start[v + 1]; ++k)
        if (chart_.corner_triangles[k] < nt_) moves[chart_.corner_triangles[k]] = 1;
    }
    std::vector<Index> out;
    for (Index t = 0; t < nt_; ++t)
      if (moves[t]) out.push_back(t);
    return out;
  }

  // Of `candidates`, the slid triangles turned against (or flat on) the frame's own, where the
  // frame's has area.
  std::vector<Index> turned(const Positions3& y, const std::vector<Index>& candidates) const {
    std::vector<Index> out;
    for (Index t : candidates) {
      const Triangle& tri = tris_[t];
      if (normals_[t].isZero(0)) continue;
      const Vec3 n = (y[tri[1]] - y[tri[0]]).cross(y[tri[2]] - y[tri[0]]);
      if (!(n.dot(normals_[t]) > 0)) out.push_back(t);
    }
    return out;
  }

  double step_bound(const Direction& dir, std::vector<double>* roots) const {
    Positions2 node_d(chart_.uv.size(), Vec2::Zero());
    for (Index i = 0; i < m_; ++i) node_d[setup_.movable[i]] = dir.d[i];
    return max_step(setup_, node_uv_, node_d, roots);
  }

  // A vertex still on its chart vertex was modelled with its tangent plane's least-squares map;
  // its chart step is the one that moves it, in the wedge that holds that step, as the model
  // meant: the wedge's own map inverted on the model's 3D motion.
  Vec2 redirected(Index i, const Vec2& d) const {
    const Index v = setup_.movable[i];
    const Vec3 motion = T_[i] * d;
    Vec2 best = d;
    double best_score = -INFINITY;
    for (Index k = chart_.corner_start[v]; k < chart_.corner_start[v + 1]; ++k) {
      const Index t = chart_.corner_triangles[k];
      const Mat32& Tk = jacobian_[t];
      const Eigen::Matrix2d A = Tk.transpose() * Tk;
      if (!(std::abs(A.determinant()) > 0)) continue;
      const Vec2 dk = A.inverse() * (Tk.transpose() * motion);
      if (!(dk.norm() > 0)) continue;
      const double score = wedge_score(chart_, t, v, dk);
      if (score > best_score) {
        best_score = score;
        best = dk;
      }
    }
    return best;
  }

  Direction solved() {
    Positions2 d;
    for (Index i = 0; i < m_; ++i) g_movable_[i] = g_[setup_.movable[i]];
    if (!system_.solve(T_, held_, g_movable_, d)) d.assign(m_, Vec2::Zero());
    for (Index i = 0; i < m_; ++i)
      if (on_vertex_[i] && !held_[i] && switched_[i] == 0 && !d[i].isZero(0))
        d[i] = redirected(i, d[i]);
    return direction(std::move(d));
  }

  // Model and truth disagree where a vertex sits on a chart vertex or edge, and Phi bends there:
  // a vertex whose true first-order change goes up is given the Jacobian of the triangle it would
  // enter, and re-solved; after three such changes it is held for this step.
  Direction model_step() {
    Direction dir = solved();
    for (int round = 0; dir.slope > 0.5 * dir.model && round < 12; ++round) {
      bool changed = false;
      for (Index i = 0; i < m_; ++i) {
        const Index v = setup_.movable[i];
        if (held_[i] || !(g_[v].dot(dir.T_true[i] * dir.d[i]) > 0)) continue;
        if (switched_[i] < 3 && !T_[i].isApprox(dir.T_true[i], 0)) {
          T_[i] = dir.T_true[i];
          ++switched_[i];
        } else {
          held_[i] = 1;
        }
        changed = true;
      }
      if (!changed) break;
      dir = solved();
    }
    return dir;
  }

  // Holds every movable corner of triangle t; false when none was free.
  bool hold_triangle(Index t) {
    bool any = false;
    for (Index v : tris_[t]) {
      const Index i = setup_.movable_slot[v];
      if (i >= 0 && !held_[i]) held_[i] = any = true;
    }
    return any;
  }

  // A step that a few triangles cut short (about to turn over in the chart, or against the frame)
  // would leave the rest of the patch stuck: those triangles' vertices are held and the step
  // solved again, within a budget of held vertices. Returns the step, and the held one if any.
  std::vector<Direction> steps_with_holds(Direction dir) {
    std::vector<Direction> candidates{std::move(dir)};
    Index budget = hold_cap_;
    for (int round = 0; round < 12; ++round) {
      std::vector<double> roots;
      const double alpha_max = step_bound(candidates.back(), &roots);
      std::vector<Index> culprits;
      if (alpha_max < 1) {
        for (Index t = 0; t < nt_; ++t)
          if (roots[t] < 1) culprits.push_back(t);
      } else {
        culprits = turned(trial(candidates.back(), std::min(1.0, 0.8 * alpha_max)).x,
                          moving_triangles(candidates.back()));
      }
      if (culprits.empty()) break;
      const std::vector<char> before = held_;
      bool any = false;
      for (Index t : culprits) any = hold_triangle(t) || any;
      const Index added = static_cast<Index>(std::count(held_.begin(), held_.end(), 1) -
                                             std::count(before.begin(), before.end(), 1));
      if (!any || added > budget) {
        held_ = before;
        break;
      }
      budget -= added;
      Direction pinned = solved();
      if (candidates.size() == 1)
        candidates.push_back(std::move(pinned));
      else
        candidates.back() = std::move(pinned);
    }
    return candidates;
  }

  // Whatever still climbs to first order is held: the direction is then a descent.
  void descend(Direction& c) const {
    if (c.slope < 0) return;
    c.slope = 0;
    for (Index i = 0; i < m_; ++i) {
      const double rise = g_[setup_.movable[i]].dot(c.T_true[i] * c.d[i]);
      if (rise > 0) {
        c.d[i] = Vec2::Zero();
        c.entered[i] = result_.where[i].triangle;
      } else {
        c.slope += rise;
      }
    }
  }

  // From 0.8 of the step that turns a chart triangle over (at most 1), halved until the energy
  // falls by Armijo's rule; the vertices of slid triangles that would turn against the frame stay
  // where they are and the rest take the step (until nothing turns: a triangle whose corners all
  // stay is as it is now). The candidate reaching the lower energy wins.
  bool line_search(const std::vector<Direction>& candidates, Trial& best, double& E_new) const {
    bool accepted = false;
    for (const Direction& c : candidates) {
      if (!(c.slope < 0)) continue;
      double alpha = std::min(1.0, 0.8 * step_bound(c, nullptr));
      const std::vector<Index> moving = moving_triangles(c);
      for (int halving = 0; halving < 40 && alpha > 0; ++halving, alpha *= 0.5) {
        Direction part = c;
        Trial t = trial(part, alpha);
        // Until no triangle turns; a turned triangle none of whose corners moves (turned already,
        // or flat to round-off) cannot be helped here and ends the loop.
        for (bool stopped = true; stopped && part.slope < 0;) {
          stopped = false;
          for (Index q : turned(t.x, moving))
            for (Index v : tris_[q]) {
              const Index i = setup_.movable_slot[v];
              if (i < 0 || part.d[i].isZero(0)) continue;
              part.slope -= g_[v].dot(part.T_true[i] * part.d[i]);
              part.d[i] = Vec2::Zero();
              t.uv[i] = result_.uv[i];
              t.where[i] = result_.where[i];
              t.x[v] = x_[v];
              stopped = true;
            }
        }
        if (!(part.slope < 0)) continue;
        const double e = held_rotation_energy(setup_, t.x, s_, R_, nullptr);
        if (std::isfinite(e) && e < E_ && e <= E_ + 1e-4 * alpha * part.slope) {
          if (!accepted || e < E_new) {
            E_new = e;
            best = std::move(t);
          }
          accepted = true;
          break;
        }
      }
    }
    return accepted;
  }

  const ElasticSetup& setup_;
  const Chart& chart_;
  const std::vector<Triangle>& tris_;
  const Index nt_;
  const Index m_;
  const Positions3& frame_;
  const std::vector<Vec3>& normals_;
  const double s_;
  ElasticResult& result_;        // uv and where: the movable vertices' chart points so far
  Positions3 x_;                 // the slid patch (local ids)
  Positions2 node_uv_;           // every chart node's point: movable ones follow the slide
  std::vector<Mat32> jacobian_;  // the frame over each chart triangle
  std::vector<char> on_vertex_;  // still on its own chart node
  std::vector<Mat32> T_;         // the model's Jacobians this step
  std::vector<char> held_;       // held this step
  std::vector<int> switched_;    // model Jacobians changed this step
  const Index hold_cap_;
  StepSystem system_;
  std::vector<Mat32> R_;  // the rotations of the current round
  Positions3 g_;          // the held-rotation energy's gradient at x_
  Positions3 g_movable_;  // g_ of the movable vertices, for the step system
  double E_ = 0;          // the held-rotation energy at x_
};

}  // namespace

ElasticSetup elastic_setup(const Positions3& points, const std::vector<Triangle>& triangles,
                           const std::vector<std::vector<Index>>& loops, Index outer_loop,
                           const std::vector<Index>& movable) {
  ElasticSetup setup;
  setup.chart = disk_chart(points, triangles, loops, outer_loop);
  setup.movable = movable;
  setup.movable_slot.assign(points.size(), -1);
  for (size_t i = 0; i < movable.size(); ++i)
    setup.movable_slot[movable[i]] = static_cast<Index>(i);
  setup.rest_inverse.resize(triangles.size());
  double area = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    setup.rest_inverse[t] = rest_inverse(points[tri[0]], points[tri[1]], points[tri[2]]);
    area += 0.5 * (points[tri[1]] - points[tri[0]]).cross(points[tri[2]] - points[tri[0]]).norm();
  }
  setup.bind_area = area;
  // Uniform weights: every triangle's stretch counts the same (small triangles are where skin
  // creases); the mean area only gives the energy the units of an area.
  setup.triangle_weight = triangles.empty() ? 0.0 : area / static_cast<double>(triangles.size());
  // K_ij = sum_t 2 w G_ti . G_tj over movable pairs.
  std::vector<Triplet> entries;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Matrix2d& D = setup.rest_inverse[t];
    if (!has_rest_shape(D)) continue;
    const std::array<Vec2, 3> G = gradient_rows(D);
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const Index i = setup.movable_slot[triangles[t][k]],
                    j = setup.movable_slot[triangles[t][l]];
        if (i >= 0 && j >= 0)
          entries.emplace_back(i, j, 2 * setup.triangle_weight * G[k].dot(G[l]));
      }
  }
  // Every movable vertex keeps a diagonal entry, even with no rest shape around it.
  for (size_t i = 0; i < movable.size(); ++i) entries.emplace_back(i, i, 0.0);
  const Index m = static_cast<Index>(movable.size());
  Eigen::SparseMatrix<double, Eigen::RowMajor> K(m, m);
  K.setFromTriplets(entries.begin(), entries.end());
  K.makeCompressed();
  setup.metric_start.assign(K.outerIndexPtr(), K.outerIndexPtr() + m + 1);
  setup.metric_column.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
  setup.metric_value.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
  if (m > 0)
    setup.step_multigrid =
        step_multigrid(setup.metric_start, setup.metric_column, setup.metric_value);
  return setup;
}

double elastic_energy(const ElasticSetup& setup, const Positions3& x, double scale) {
  const auto& tris = setup.chart.triangles;
  std::vector<Vec3> normals(setup.chart.patch_triangle_count);
  for (size_t t = 0; t < normals.size(); ++t)
    normals[t] = (x[tris[t][1]] - x[tris[t][0]]).cross(x[tris[t][2]] - x[tris[t][0]]);
  return arap_energy(setup, x, scale, normals);
}

ElasticResult relax_patch(const ElasticSetup& setup, const Positions3& frame,
                          const ElasticOptions& options) {
  const Chart& chart = setup.chart;
  const auto& tris = chart.triangles;
  const Index nt = chart.patch_triangle_count;
  const Index m = static_cast<Index>(setup.movable.size());
  ElasticResult result;
  result.uv.resize(m);
  result.where.resize(m);
  result.position.resize(m);
  // The start: every movable vertex exactly at its frame position, on a triangle around it.
  const auto at_start = [&](Index i) {
    const Index v = setup.movable[i];
    result.uv[i] = chart.uv[v];
    const Index t = chart.corner_triangles[chart.corner_start[v]];
    ChartPoint p{t, {0, 0, 0}};
    for (int k = 0; k < 3; ++k) p.weight[k] = tris[t][k] == v ? 1.0 : 0.0;
    result.where[i] = p;
    result.position[i] = frame[v];
  };
  for (Index i = 0; i < m; ++i) at_start(i);
  if (m == 0) return result;
  std::vector<Vec3> frame_normals(nt);
  double frame_area = 0;
  for (Index t = 0; t < nt; ++t) {
    const Triangle& tri = tris[t];
    frame_normals[t] = (frame[tri[1]] - frame[tri[0]]).cross(frame[tri[2]] - frame[tri[0]]);
    frame_area += 0.5 * frame_normals[t].norm();
  }
  const double s = setup.bind_area > 0 ? std::sqrt(frame_area / setup.bind_area) : 1.0;
  result.scale = s;
  result.energy_before = result.energy_after = arap_energy(setup, frame, s, frame_normals);
  if (!std::isfinite(result.energy_before) || !std::isfinite(s))
    throw Error(ErrorKind::Numeric, "the frame's elastic energy is not finite");
  // A frame that is the bind up to a rigid motion and a uniform scale has nothing to undo; its
  // energy is round-off.
  if (result.energy_before <= 1e-20 * setup.bind_area) {
    result.stop = "at rest";
    return result;
  }
  // ARAP's local/global alternation, a fixed number of rounds: fit each triangle's rotation to
  // the slid patch (at first the frame), then lower the energy with those rotations held, on the
  // surface, to convergence. Each round's result moves smoothly with the frame; full ARAP (many
  // rounds) has minima that jump from one frame to the next.
  Relaxation relaxation(setup, frame, frame_normals, s, result);
  result.stop = "converged";
  for (int round = 0; round < options.rotation_fits; ++round) {
    relaxation.fit_rotations();
    const double E_round = relaxation.energy();
    int small_steps = 0;
    int it = 0;
    for (; it < options.max_iterations; ++it) {
      const double E_old = relaxation.energy();
      if (!relaxation.step()) break;
      ++result.iterations;
      small_steps = E_old - relaxation.energy() < options.tolerance * E_round ? small_steps + 1 : 0;
      if (small_steps >= 2) break;
    }
    if (it == options.max_iterations) result.stop = "limit";
  }
  const Positions3& x = relaxation.positions();
  // The ARAP energy cannot rise: each round starts where the last ended, with the rotations that
  // minimise it there, and only lowers it. Round-off aside; a frame whose relaxation gained
  // nothing comes back unchanged.
  result.energy_after = arap_energy(setup, x, s, frame_normals);
  if (!(result.energy_after <= result.energy_before)) {
    for (Index i = 0; i < m; ++i) at_start(i);
    result.energy_after = result.energy_before;
    result.stop = "no descent";
    return result;
  }
  for (Index i = 0; i < m; ++i) {
    result.position[i] = x[setup.movable[i]];
    if (!result.position[i].allFinite())
      throw Error(ErrorKind::Numeric, "patch vertex " + std::to_string(setup.movable[i]) +
                                          ": the slid position is not finite");
  }
  return result;
}

}  // namespace skinslide
