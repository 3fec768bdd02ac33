#pragma once
// Projected preconditioned CG on one face of SMALBE's feasible set (docs/qp_solvers.md, "Face
// solve"): min 1/2 x^T A x - b^T x subject to Q x = 0 and x_A = r (the active components held at
// their bounds, the free ones unconstrained), i.e. PCPG as for the tied problem with the face's
// projector P_F (tfeti_FaceProjector.hpp) in place of P:
//   w = P_F g,  z = P_F M w,  p = z + beta p,  x -= alpha p,  g -= alpha A p,
// from x in the face's affine set (so every iterate stays in it: p is in range(P_F)). M is
// SMALBE's preconditioner (for FETI P M P + Q / rho, which P_F turns into P_F M P_F), or none.
// Stiff components (3D friction's circles whose curvature nu / r in the face's Hessian outweighs
// A, tfeti_SmalbeFacePhase_def.hpp): M knows nothing of that diagonal term, and each such
// component is an eigenvalue of the preconditioned operator far above the others, a CG step
// apiece and more once orthogonality is lost (docs/qp_solvers.md, "Stiff circles"). They are
// taken out of M's input and output and scaled by the inverse of their own diagonal instead:
//   z = P_F (E_c M E_c w + D_s^{-1} w),   E_c zero on the stiff components, one elsewhere,
// symmetric and positive definite on the face whenever M is. E_c M E_c still approximates the
// inverse of A with those components free, where the face holds them nearly still: a gap of
// the rank of their count, which at hundreds of stiff circles still costs hundreds of steps.
// Stops when ||P_F g|| <= tolerance (the free rows' gradient: P_F g is zero on the active
// rows) or, with a reduction, at that share of its start, or fails after "maximum iterations" or on
// a direction of non-positive curvature.
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <Teuchos_RCP.hpp>

#include <algorithm>
#include <vector>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_FaceProjector.hpp"

namespace tfeti {

// Components preconditioned by their own diagonal (see above): global indices, sorted, and the
// inverse of the diagonal at each.
template <class S>
struct FaceStiffComponents {
  std::vector<long long> indices;
  std::vector<S> inverseDiagonal;
  bool empty() const { return indices.empty(); }
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
           FaceStiffComponents<S> stiff = FaceStiffComponents<S>())
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
  FaceStiffComponents<S> stiff_;

  void precondition(const MV& w, MV& z) const {
    using BT = BoundTraits<S, MV>;
    if (M_.is_null() && stiff_.empty()) {
      MVT::Assign(w, z);
      return;
    }
    std::vector<S> ws;
    const MV* in = &w;
    Teuchos::RCP<MV> masked;
    if (!stiff_.empty()) {
      ws = BT::gatherAt(w, stiff_.indices);
      masked = MVT::CloneCopy(w);
      BT::setAt(stiff_.indices, std::vector<S>(ws.size(), S(0)), *masked);
      in = masked.get();
    }
    if (M_.is_null())
      MVT::Assign(*in, z);
    else
      OPT::Apply(*M_, *in, z);
    if (!stiff_.empty()) {
      for (std::size_t i = 0; i < ws.size(); ++i) ws[i] *= stiff_.inverseDiagonal[i];
      BT::setAt(stiff_.indices, ws, z);
    }
    face_.apply(z, z);
  }
};

}  // namespace tfeti
