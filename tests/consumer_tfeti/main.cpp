// The Poisson problem -Laplace u = 1 on the unit square, u = 0 on x = 0, in 3 x 3 subdomains
// whose matrices this program assembles itself (bilinear squares), solved by tfeti::FetiSolver and
// compared with a direct solve of the untorn problem.
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace {
// K and f of -Laplace u = 1 on the elements (squares of side h, 4 nodes counter-clockwise) of a
// mesh.
void assemble(const tfeti::SubdomainMesh& m, double h, tfeti::CsrMatrix& K,
              std::vector<double>& f) {
  static const double ke[4][4] = {
      {4, -1, -2, -1}, {-1, 4, -1, -2}, {-2, -1, 4, -1}, {-1, -2, -1, 4}};
  std::vector<int> ri, ci;
  std::vector<double> v;
  f.assign(m.numNodes(), 0.0);
  for (int e = 0; e < m.numElements(); ++e) {
    const int* q = &m.elements.nodes[m.elements.offsets[e]];
    for (int a = 0; a < 4; ++a) {
      f[q[a]] += h * h / 4;
      for (int b = 0; b < 4; ++b) {
        ri.push_back(q[a]);
        ci.push_back(q[b]);
        v.push_back(ke[a][b] / 6);
      }
    }
  }
  K = tfeti::csrFromTriplets(m.numNodes(), m.numNodes(), ri, ci, v);
}
}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 3, 3, 4, 4);
  const double h = 1.0 / 12;
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(comm->getRank(), 9, comm->getSize())) {
    tfeti::SubdomainData d;
    d.mesh = rect.subdomain(s);
    assemble(d.mesh, h, d.K, d.f);
    local.push_back(std::move(d));
  }
  Teuchos::ParameterList params;
  params.sublist("PCPG").set("Relative tolerance", 1e-10);
  tfeti::FetiSolver solver(comm, 9, std::move(local), params);
  const auto result = solver.solve();

  // The untorn problem, Dirichlet rows and columns replaced by the identity.
  const tfeti::SubdomainMesh whole = rect.wholeMesh();
  tfeti::CsrMatrix K;
  std::vector<double> f, u(whole.numNodes());
  assemble(whole, h, K, f);
  std::vector<char> fixed(whole.numNodes(), 0);
  for (int n : whole.dirichletNodes) fixed[n] = 1;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (fixed[i] || fixed[K.colInd[k]]) K.values[k] = i == K.colInd[k] ? 1.0 : 0.0;
  for (int i = 0; i < K.rows; ++i)
    if (fixed[i]) f[i] = 0.0;
  auto direct = tfeti::createLocalSolver("cholmod");
  direct->factorize(K);
  direct->solve(f.data(), u.data());

  double err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (int n = 0; n < mesh.numNodes(); ++n)
      err = std::max(err, std::abs(solver.solution(i)[n] - u[mesh.globalNode[n]]));
  }
  for (double x : u) scale = std::max(scale, std::abs(x));
  double globalErr = err;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &err, &globalErr);
  std::cout << "tfeti_only: " << result.iterations << " iterations, error " << globalErr / scale
            << "\n";
  return result.converged && globalErr / scale < 1e-8 ? 0 : 1;
}
