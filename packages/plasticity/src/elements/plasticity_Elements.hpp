#pragma once
// Kokkos kernels assembling stiffness, loads and recovered stresses on meshes of the
// isoparametric elements of plasticity_ElementTypes.hpp, in 2D (plane strain: Tri3, Tri6,
// Quad4, Quad9) and 3D (Tet4, Tet10, Hex8, Hex27) through one code path: the spatial dimension
// is the element type's. Unknowns: dim per node, interleaved (dof dim*node + component).
#include <Kokkos_Core_fwd.hpp>  // KOKKOS_INLINE_FUNCTION and View declarations; kernels in .cpp

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_ElementTypes.hpp"
#include "plasticity_MaterialLaw.hpp"
#include "tfeti_CsrMatrix.hpp"

namespace plasticity {

// A mesh of one element type, whose dimension is the mesh's spatial dimension. Elements must
// have a positive Jacobian (counter-clockwise in 2D, right-handed in 3D, as Gmsh writes them).
struct ElementMesh {
  ElementType type = ElementType::Quad4;
  std::vector<double> coords;     // dim() coordinates per node
  std::vector<int> connectivity;  // nodesPerElement(type) per element, Gmsh order
  int dim() const { return spatialDimension(type); }
  int numNodes() const { return static_cast<int>(coords.size()) / dim(); }
  int numElements() const { return static_cast<int>(connectivity.size()) / nodesPerElement(type); }
  // The digest (tfeti::Digest) of type, coords and connectivity when the kernels last found them
  // valid ({0, 0}: never). A Newton method evaluates f_int and the tangent on the same reference
  // mesh many times; the kernels repeat the connectivity and Jacobian checks only when the digest
  // no longer matches (on step-42 at 64^3 plastic they were 1.6 % of the samples). Copies carry
  // it with the data. The kernels write it: one mesh is not for concurrent calls.
  mutable std::array<std::uint64_t, 2> checkedDigest{};
};

// Stiffness matrix (tangent of the law at zero strain) of the whole mesh, dim dofs per node;
// the pattern holds every node pair sharing an element. Throws std::invalid_argument naming
// the element when connectivity is out of range or the Jacobian determinant is not positive
// at some Gauss point or node.
tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const MaterialLaw& law);
tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const ElasticLaw& law);

// Consistent nodal forces of a uniform body force b (dim components; force per unit volume, in
// 2D per unit area of the unit-thickness plane-strain slice).
std::vector<double> assembleBodyForce(const ElementMesh& mesh, const double b[]);

// Consistent nodal forces of a uniform traction t (dim components, force per unit area; in 2D
// per unit edge length, i.e. stress times the unit thickness) on the given faces (edges in 2D).
// `faces` lists nodesPerFace(mesh.type) nodes per face in the order of Gmsh's faceType(type)
// element (Line2/Line3 edges: the two ends, then the middle; Tri3/Tri6, Quad4/Quad9 faces:
// corners cyclically, then mid-edge nodes and centre), either orientation. Each must be a face
// of some element with its nodes where that ordering puts them, which catches faces of the
// wrong order or with a misplaced mid node. Throws std::invalid_argument naming the face
// (the edge in 2D) otherwise, or when its area is zero.
std::vector<double> assembleSurfaceTraction(const ElementMesh& mesh, const std::vector<int>& faces,
                                            const double t[]);
// The 2D name of the same.
inline std::vector<double> assembleEdgeTraction(const ElementMesh& mesh,
                                                const std::vector<int>& edges, const double t[]) {
  return assembleSurfaceTraction(mesh, edges, t);
}

// Stress components as stored in StressField, per Gauss point and per node: the Voigt order of
// plasticity_MaterialLaw.hpp (sigma_zz is non-zero in plane strain; yz, xz vanish there), then
// von Mises.
enum StressComponent {
  kSxx = kXX,
  kSyy = kYY,
  kSzz = kZZ,
  kSyz = kYZ,
  kSxz = kXZ,
  kSxy = kXY,
  kVonMises = kNumVoigt,
  kNumStressComponents
};

struct StressField {
  int gaussPointsPerElement = 0;
  // [(e * gaussPointsPerElement + q) * kNumStressComponents + c]: the law's stress at the
  // Gauss point (the only place a history-dependent law has it), and its von Mises value.
  std::vector<double> gauss;
  // [(e * gaussPointsPerElement + q) * dim + i]: physical position of the Gauss point.
  std::vector<double> gaussCoords;
  // [n * kNumStressComponents + c]: per element, the Gauss-point stresses are extrapolated to
  // the element's nodes (by the polynomial through the Gauss points: constant for Tri3 and Tet4,
  // linear for Tri6 and Tet10, (tri)linear for Quad4 and Hex8, (tri)quadratic for Quad9 and
  // Hex27) and the node takes the mean over the elements sharing it. Von Mises is the invariant
  // of the averaged tensor.
  std::vector<double> nodal;

  double atGaussPoint(int e, int q, int c) const {
    return gauss[(static_cast<std::size_t>(e) * gaussPointsPerElement + q) * kNumStressComponents +
                 c];
  }
  double atNode(int n, int c) const {
    return nodal[static_cast<std::size_t>(n) * kNumStressComponents + c];
  }
};

// Von Mises equivalent stress sqrt(3 J2) of a Voigt stress. Host-only (std::sqrt), as are the
// kernels on the Serial backend.
KOKKOS_INLINE_FUNCTION double vonMises(const double s[kNumVoigt]) {
  const double a = s[kXX] - s[kYY], b = s[kYY] - s[kZZ], c = s[kZZ] - s[kXX];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * s[kXY] * s[kXY] + 3 * s[kYZ] * s[kYZ] +
                   3 * s[kXZ] * s[kXZ]);
}
// The plane-strain case (sigma_yz = sigma_xz = 0).
KOKKOS_INLINE_FUNCTION double vonMises(double sxx, double syy, double sxy, double szz) {
  const double s[kNumVoigt] = {sxx, syy, szz, 0, 0, sxy};
  return vonMises(s);
}

// Stresses of the displacement u (dim dofs per node) through the law.
StressField recoverStresses(const ElementMesh& mesh, const MaterialLaw& law,
                            const std::vector<double>& u);

// Building blocks shared with the other kernel files of this package (plasticity_TotalLagrangian),
// so that they validate, gather and scatter exactly as these kernels do. Not a user API.
namespace detail {
using HostView2 = Kokkos::View<double**, Kokkos::HostSpace>;
using HostView3 = Kokkos::View<double***, Kokkos::HostSpace>;
// "<type> element <e>", the prefix of every per-element error message.
std::string elementLabel(const ElementMesh& mesh, int e);
// Validated element coordinates (ne, dim npe); throws as assembleStiffness does.
HostView2 checkedElementCoords(const ElementMesh& mesh);
// Element displacements (ne, dim npe); throws when u does not have dim entries per node.
HostView2 elementDisplacements(const ElementMesh& mesh, const std::vector<double>& u);
// The CSR pattern of the stiffness (node pairs sharing an element, dim dofs each), values zero.
tfeti::CsrMatrix stiffnessPattern(const ElementMesh& mesh);
// Adds the element blocks Ke (element e at e - first) of the elements [first, last) into K, whose
// pattern is stiffnessPattern(mesh).
void addElementMatrices(const ElementMesh& mesh, const HostView3& Ke, int first, int last,
                        tfeti::CsrMatrix& K);
// Element vectors fe (ne, dim npe) summed into a nodal vector (dim per node).
std::vector<double> scatterVector(const ElementMesh& mesh, const HostView2& fe);
// The StressField of Gauss-point stresses sg (ne, ngp, 6: Voigt) at positions xg (ne, ngp,
// dim): von Mises added, nodal values extrapolated and averaged.
StressField stressField(const ElementMesh& mesh, const HostView3& sg, const HostView3& xg);
}  // namespace detail

}  // namespace plasticity
