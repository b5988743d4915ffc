// The direction of one elastic step (lib/elastic/README.md rule 7): a Gauss-Newton step in the
// chart, T^T (K x I3) T d = -T^T g over the movable vertices, solved inexactly by conjugate
// gradients preconditioned with the bind's own metric K, factorised once per patch at bind time.
// In each vertex's tangent coordinates (d_i = S_i^-1 xi_i, S_i^T S_i = T_i^T T_i) the system's
// blocks are K_ij Q_i^T Q_j with Q = T S^-1 orthonormal: K x I2 where neighbouring tangent planes
// agree, whatever the chart's distortion or the frame's stretch. So the bind-time factor is a
// close preconditioner in every frame, and no frame assembles or factorises anything.
#pragma once

#include <vector>

#include "core/types.h"
#include "elastic/arap.h"
#include "solve/sparse_cholesky.h"

namespace skinslide {

/// The bind's ARAP metric over a patch's movable vertices, K_ij = sum_t 2 w G_ti . G_tj (G_t:
/// the triangle's gradient rows; README rule 3), and the Cholesky factor of K + shift I. Plain
/// data, built once per patch, shared read-only by every frame.
struct ElasticMetric {
  /// K in compressed rows, both triangles, columns ascending.
  std::vector<Index> start;
  std::vector<Index> column;
  std::vector<double> value;
  /// A whisper of the identity (1e-12 of K's mean diagonal): keeps the factor and every step
  /// system definite where triangles without a rest shape leave a vertex without stiffness.
  double shift = 0;
  CholeskyFactor factor;
  Index size() const { return static_cast<Index>(start.size()) - 1; }
};

/// \param movable_slot per patch vertex (local id) its movable index, or -1.
/// \param count the number of movable vertices. \throw Error(Numeric) if K cannot be factorised.
ElasticMetric elastic_metric(const ArapTriangles& mesh, const std::vector<Index>& movable_slot,
                             Index count);

/// How far the conjugate gradients go (tests vary it; the defaults are rule 7's).
struct DirectionSolve {
  /// Stop once |r| <= tolerance |r_0|. A looser solve changes the slides (a step's direction
  /// decides which triangles tighten first), so it is tight.
  double tolerance = 1e-4;
  /// Preconditioned iterations at most (each one back-solve with the factor): the few where the
  /// frame's tangent planes turn against the bind's (creases, a jaw opening) converge slowly.
  int max_iterations = 8;
};

/// Vertex i's change of variables d_i = S^-1 xi_i and Q = T S^-1 (S^T S = T^T T): Q has
/// orthonormal columns. A Jacobian near rank one (singular values' ratio under 1e-4: the frame
/// crushed towards a line or a point there) has no such frame: the vertex is `crushed`, and
/// stays for the step (a chart step there hardly moves it on the surface, and the bind's metric
/// would misjudge its row).
struct TangentFrame {
  Eigen::Matrix2d S_inverse = Eigen::Matrix2d::Identity();
  Mat32 Q = Mat32::Zero();
  bool crushed = true;
};

/// The sum of a[i] . b[i]: the dot product of two per-vertex 2D fields.
double dot(const Positions2& a, const Positions2& b);

/// Per movable vertex its tangent frame for the Jacobians T (3x2: chart step -> 3D motion).
std::vector<TangentFrame> tangent_frames(const std::vector<Mat32>& T);

/// Work arrays of step_direction, kept from step to step (one per frame in flight).
struct DirectionWork {
  std::vector<char> stays;  ///< held or crushed
  Positions2 r, x, z, p, Ap, permuted;
  Positions3 motion;
};

/// Preconditioned conjugate gradients (Hestenes & Stiefel 1952) from x = 0 on A x = b: on entry
/// work.r holds b, on return work.x the iterate and work.r its residual. `precondition(z)`
/// applies M^-1 in place, `apply(p, Ap)` writes A p. Iterates while fewer than max_iterations are
/// done and more(r) holds; stops early when r^T M^-1 r or p^T A p is not positive (solved
/// exactly, or A not definite along p). Returns the iterations done. The one loop of both
/// solvers' step systems (rule 7 and the map's M3).
template <class Precondition, class Apply, class More>
int conjugate_gradients(DirectionWork& work, int max_iterations, Precondition precondition,
                        Apply apply, More more) {
  Positions2 &r = work.r, &x = work.x, &z = work.z, &p = work.p, &Ap = work.Ap;
  const size_t m = r.size();
  x.assign(m, Vec2::Zero());
  z.resize(m);
  p.resize(m);
  Ap.resize(m);
  double rz = 0;
  int done = 0;
  while (done < max_iterations && more(r)) {
    z = r;
    precondition(z);
    const double rz_next = dot(r, z);
    if (!(rz_next > 0)) break;
    if (done == 0) {
      p = z;
    } else {
      const double beta = rz_next / rz;
      for (size_t i = 0; i < m; ++i) p[i] = z[i] + beta * p[i];
    }
    rz = rz_next;
    apply(p, Ap);
    const double pAp = dot(p, Ap);
    if (!(pAp > 0)) break;
    const double a = rz / pAp;
    for (size_t i = 0; i < m; ++i) {
      x[i] += a * p[i];
      r[i] -= a * Ap[i];
    }
    ++done;
  }
  return done;
}

struct StepDirection {
  Positions2 d;         ///< per movable vertex, its chart step
  int iterations = 0;   ///< conjugate-gradient iterations
  bool finite = true;   ///< false when the solve met a non-finite number (d is then zero)
  bool capped = false;  ///< stopped at its iteration budget, short of its tolerance
  double residual = 0;  ///< |r| / |r_0| where it stopped (0 when it had nothing to solve)
};

/// The step direction given each movable vertex's tangent frame (from its Jacobian), the
/// energy's 3D gradient g there, and the vertices held in place (`held`, per movable vertex; an
/// empty vector holds none; crushed ones are held too). Truncated conjugate gradients from zero
/// lower the Gauss-Newton model at every iteration, so d is a descent direction of the model
/// whenever g is not normal to every free vertex's tangent plane.
StepDirection step_direction(const ElasticMetric& metric, const std::vector<TangentFrame>& frames,
                             const Positions3& gradient, const std::vector<char>& held,
                             DirectionWork& work, const DirectionSolve& solve = {});

/// The last step_direction's solution (in `work`) with the vertices in `held` held: their
/// steps removed, then the system relaxed around them by symmetric Gauss-Seidel sweeps over the
/// free vertices within a few rings of a held one. A held vertex changes the step mostly near
/// itself, so this costs a small share of a solve and keeps the rest of the patch's step.
StepDirection held_direction(const ElasticMetric& metric, const std::vector<TangentFrame>& frames,
                             const Positions3& gradient, const std::vector<char>& held,
                             DirectionWork& work);

}  // namespace skinslide
