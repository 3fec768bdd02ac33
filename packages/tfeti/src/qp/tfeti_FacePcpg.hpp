#pragma once
// Projected preconditioned CG on one face of SMALBE's feasible set (docs/qp_solvers.md, "Face
// solve"): min 1/2 x^T A x - b^T x subject to Q x = 0 and x_A = r (the active components held at
// their bounds, the free ones unconstrained), i.e. PCPG as for the tied problem with the face's
// projector P_F (tfeti_FaceProjector.hpp) in place of P:
//   w = P_F g,  z = P_F M w,  p = z + beta p,  x -= alpha p,  g -= alpha A p,
// from x in the face's affine set (so every iterate stays in it: p is in range(P_F)). M is
// SMALBE's preconditioner (for FETI P M P + Q / rho, which P_F turns into P_F M P_F), or none.
// Stiff circles (3D friction's circles whose curvature nu / r in the face's Hessian outweighs A,
// tfeti_SmalbeFacePhase_def.hpp): M approximates A^{-1}, but the face's Hessian is A + E K E^T
// (E the circles' unit tangents, K their curvatures), and each stiff tangent that M ignores is
// an eigenvalue of the preconditioned operator far above the others, a CG step apiece and more
// once orthogonality is lost (docs/qp_solvers.md, "Stiff circles"). The preconditioner is then
// M's inverse updated by the curvature, by Woodbury's identity:
//   (M^{-1} + E K E^T)^{-1} = M - (M E) C^{-1} (M E)^T,   C = K^{-1} + E^T M E   (s x s),
// symmetric and positive definite whenever M is; z = P_F of it applied to w. M E is computed
// once per face (M applied to the stiff circles' components, cached for the face phase); each
// step adds a gather of 2 s values, an s x s solve and an update by the s columns of M E.
// Stops when ||P_F g|| <= tolerance (the free rows' gradient: P_F g is zero on the active
// rows) or, with a reduction, at that share of its start, or fails after "maximum iterations" or on
// a direction of non-positive curvature.
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_RCP.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>

#include <algorithm>
#include <vector>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_FaceProjector.hpp"

namespace tfeti {

// The stiff circles of a face (see above): both components of each, its unit tangent, M E (one
// column per circle; null when there is no M, which then stands for the identity and E is its
// own image) and the Cholesky factor of C = K^{-1} + E^T M E (column-major, lower).
template <class S, class MV>
struct FaceStiffCircles {
  std::vector<long long> components;
  std::vector<S> t0, t1;
  Teuchos::RCP<MV> ME;
  std::vector<S> factor;
  int count() const { return static_cast<int>(t0.size()); }
  bool empty() const { return t0.empty(); }
};

template <class S>
struct FacePcpgResult {
  bool converged = false;
  int iterations = 0;           // PCPG steps = multiplications by A
  S projectedGradientNorm = 0;  // final ||P_F g|| (the recursive g)
};

template <class S, class MV, class OP>
class FacePcpg {
 public:
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;

  // reduction > 0: stop already at ||P_F g|| <= reduction * (its value at the start), when that
  // is looser than the tolerance.
  FacePcpg(Teuchos::RCP<const OP> A, Teuchos::RCP<const OP> M, const FaceProjector<S, MV, OP>& face,
           S tolerance, int maxIterations, S reduction = S(0),
           FaceStiffCircles<S, MV> stiff = FaceStiffCircles<S, MV>())
      : A_(std::move(A)),
        M_(std::move(M)),
        face_(face),
        tol_(tolerance),
        maxIter_(maxIterations),
        reduction_(reduction),
        stiff_(std::move(stiff)) {}

  // x: in the face's affine set on entry, the face's minimizer on exit; g: A x - b on entry,
  // updated recursively.
  FacePcpgResult<S> solve(MV& x, MV& g) const {
    auto w = MVT::Clone(x, 1), z = MVT::Clone(x, 1), p = MVT::Clone(x, 1), q = MVT::Clone(x, 1);
    FacePcpgResult<S> r;
    std::vector<S> dot(1), nrm(1);
    face_.apply(g, *w);
    MVT::MvNorm(*w, nrm);
    const S tol = std::max(tol_, reduction_ * S(nrm[0]));
    precondition(*w, *z);
    MVT::Assign(*z, *p);
    MVT::MvDot(*w, *z, dot);
    S wz = dot[0];
    while (!(nrm[0] <= tol) && r.iterations < maxIter_) {
      OPT::Apply(*A_, *p, *q);
      ++r.iterations;
      MVT::MvDot(*p, *q, dot);
      if (!(dot[0] > S(0))) break;  // A not positive definite on the face, or breakdown
      const S alpha = wz / dot[0];
      MVT::MvAddMv(S(1), x, -alpha, *p, x);
      MVT::MvAddMv(S(1), g, -alpha, *q, g);
      face_.apply(g, *w);
      MVT::MvNorm(*w, nrm);
      if (nrm[0] <= tol) break;
      precondition(*w, *z);
      MVT::MvDot(*w, *z, dot);
      const S wzNew = dot[0];
      MVT::MvAddMv(S(1), *z, wzNew / wz, *p, *p);
      wz = wzNew;
    }
    r.projectedGradientNorm = nrm[0];
    r.converged = nrm[0] <= tol;
    return r;
  }

 private:
  Teuchos::RCP<const OP> A_, M_;
  const FaceProjector<S, MV, OP>& face_;
  S tol_;
  int maxIter_;
  S reduction_;
  FaceStiffCircles<S, MV> stiff_;

  void precondition(const MV& w, MV& z) const {
    using BT = BoundTraits<S, MV>;
    if (M_.is_null() && stiff_.empty()) {
      MVT::Assign(w, z);
      return;
    }
    if (M_.is_null())
      MVT::Assign(w, z);
    else
      OPT::Apply(*M_, w, z);
    if (!stiff_.empty()) {
      // z -= (M E) C^{-1} (M E)^T w = (M E) C^{-1} E^T (M w).
      const int s = stiff_.count();
      const std::vector<S> at = BT::gatherAt(z, stiff_.components);
      Teuchos::SerialDenseMatrix<int, S> c(s, 1);
      for (int k = 0; k < s; ++k) c(k, 0) = stiff_.t0[k] * at[2 * k] + stiff_.t1[k] * at[2 * k + 1];
      int info = 0;
      Teuchos::LAPACK<int, S>().POTRS('L', s, 1, stiff_.factor.data(), s, c.values(), s, &info);
      if (!stiff_.ME.is_null()) {
        MVT::MvTimesMatAddMv(S(-1), *stiff_.ME, c, S(1), z);
      } else {
        std::vector<S> v(2 * s);
        for (int k = 0; k < s; ++k)
          v[2 * k] = stiff_.t0[k] * c(k, 0), v[2 * k + 1] = stiff_.t1[k] * c(k, 0);
        BT::addAt(stiff_.components, v, S(-1), z);
      }
    }
    face_.apply(z, z);
  }
};

}  // namespace tfeti
