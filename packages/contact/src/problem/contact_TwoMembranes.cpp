#include "contact_TwoMembranes.hpp"

#include <stdexcept>
#include <string>

#include "plasticity_Q1Assembly.hpp"

namespace contact {

void TwoMembranes::validate() const {
  if (subdomainsX < 1 || subdomainsY < 1 || elementsX < 1 || elementsY < 1)
    throw std::invalid_argument("two_membranes: subdomain and element counts must be positive");
  if ((subdomainsY * elementsY) % 4 != 0)
    throw std::invalid_argument(
        "two_membranes: the elements across a membrane in y (" +
        std::to_string(subdomainsY * elementsY) +
        ") must be a multiple of 4, so that the load's jumps at y = 0.25 and y = 0.75 fall on "
        "element edges");
}

tfeti::StructuredRectangle TwoMembranes::membrane(int which) const {
  tfeti::StructuredRectangle m(which == 0 ? 0.0 : 1.0, which == 0 ? 1.0 : 2.0, 0.0, 1.0,
                               subdomainsX, subdomainsY, elementsX, elementsY);
  m.setDirichletAtX0(which == 0);
  return m;
}

namespace {
double sourceAt(int membrane, double y) {
  if (membrane == 0) return y >= 0.75 ? -3.0 : 0.0;
  return y < 0.25 ? -1.0 : 0.0;
}
}  // namespace

ContactProblemData buildTwoMembranes(const TwoMembranes& problem, const tfeti::Comm& comm) {
  problem.validate();
  const tfeti::StructuredRectangle m[2] = {problem.membrane(0), problem.membrane(1)};
  const int perMembrane = m[0].numSubdomains();
  const int N = problem.numSubdomains();
  ContactProblemData data;
  for (int s : tfeti::subdomainsOfRank(comm.getRank(), N, comm.getSize())) {
    const int which = s / perMembrane;
    tfeti::SubdomainData sd;
    sd.mesh = m[which].subdomain(s % perMembrane);
    sd.mesh.id = s;
    // The membranes are separate bodies: their nodes never glue, even at x = 1.
    for (auto& g : sd.mesh.globalNode) g += which * m[0].numGlobalNodes();
    plasticity::Q1Mesh q{sd.mesh.coords, sd.mesh.elements.nodes, 2};
    std::vector<double> source(sd.mesh.numElements());
    for (int e = 0; e < sd.mesh.numElements(); ++e) {
      double yc = 0.0;
      for (int a = 0; a < 4; ++a)
        yc += 0.25 * sd.mesh.coords[2 * sd.mesh.elements.nodes[4 * e + a] + 1];
      source[e] = sourceAt(which, yc);
    }
    plasticity::ElasticLaw unused;
    sd.K = plasticity::assembleStiffness(q, plasticity::Field::Scalar, unused);
    sd.f = plasticity::assembleBodyLoad(q, plasticity::Field::Scalar, source);
    sd.dofsPerNode = 1;
    data.local.push_back(std::move(sd));
  }
  // One row per node height on x = 1, contributed by the rank owning Ω1's copy.
  const int NX = m[0].elementsX(), NY = m[0].elementsY();
  for (int j = 0; j <= NY; ++j) {
    const auto [s1, n1] = m[0].copyOfNode(NX, j);
    const auto [s2, n2] = m[1].copyOfNode(0, j);
    if (tfeti::ownerOfSubdomain(s1, N, comm.getSize()) != comm.getRank()) continue;
    tfeti::InequalityRow row;
    row.entries = {{s1, n1, 1.0}, {perMembrane + s2, n2, -1.0}};
    row.gap = 0.0;
    data.inequalities.push_back(std::move(row));
  }
  return data;
}

}  // namespace contact
