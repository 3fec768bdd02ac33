#include "contact_Partition.hpp"

#include <metis.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace contact {

static_assert(sizeof(long long) == 8, "globalNode must hold tfeti::GO values");

namespace {

// Facet `f` of the element whose nodes start at `el`: its corners give the key; its nodes
// (midside ones included) are elementFacetNodes.
FacetKey facetKey(ElementType type, const int* el, int f) {
  const ElementType ft = facetType(type);
  const auto& local = elementFacetNodes(type, f);
  int corners[4];
  const int nc = numCorners(ft);
  for (int a = 0; a < nc; ++a) corners[a] = el[local[a]];
  return contact::facetKey(corners, nc);
}

}  // namespace

std::vector<int> UnstructuredSubdomain::boundaryNodes() const {
  const int npe = nodesPerElement(), nf = numFacets(type);
  std::unordered_map<FacetKey, int, FacetKeyHash> facetCount;
  for (int e = 0; e < numElements(); ++e)
    for (int f = 0; f < nf; ++f)
      ++facetCount[facetKey(type, &connectivity[static_cast<std::size_t>(e) * npe], f)];
  std::vector<char> onBoundary(numNodes(), 0);
  for (int e = 0; e < numElements(); ++e)
    for (int f = 0; f < nf; ++f) {
      const int* el = &connectivity[static_cast<std::size_t>(e) * npe];
      if (facetCount[facetKey(type, el, f)] != 1) continue;
      for (int a : elementFacetNodes(type, f)) onBoundary[el[a]] = 1;
    }
  std::vector<int> nodes;
  for (int n = 0; n < numNodes(); ++n)
    if (onBoundary[n]) nodes.push_back(n);
  return nodes;
}

DualGraph edgeDualGraph(const GmshBody& body) {
  const int ne = body.numElements(), npe = body.nodesPerElement(), nf = numFacets(body.type);
  if (static_cast<long long>(body.connectivity.size()) != static_cast<long long>(ne) * npe)
    throw std::invalid_argument("edgeDualGraph: body \"" + body.name +
                                "\": connectivity size does not match its element count");
  // Every element's facets, sorted by facet: the elements sharing a facet are then neighbours in
  // the list. In a valid mesh a facet has at most two elements, but a third one is kept rather
  // than dropped so that a non-manifold input cannot silently lose adjacency. (A hash map from
  // facet to its elements, one small vector each, took 2.2 % of a 1M step-42 run per rank.)
  struct ElementFacet {
    FacetKey key;
    int element;
    bool operator<(const ElementFacet& o) const {
      return key != o.key ? key < o.key : element < o.element;
    }
  };
  std::vector<ElementFacet> facets;
  facets.reserve(static_cast<std::size_t>(ne) * nf);
  for (int e = 0; e < ne; ++e)
    for (int f = 0; f < nf; ++f)
      facets.push_back(
          {facetKey(body.type, &body.connectivity[static_cast<std::size_t>(e) * npe], f), e});
  std::sort(facets.begin(), facets.end());
  // The runs of equal facets, twice: the neighbour counts, then the neighbours.
  std::vector<int> start(static_cast<std::size_t>(ne) + 1, 0);
  auto forEachPair = [&](auto&& visit) {
    for (std::size_t i = 0, n = facets.size(); i < n;) {
      std::size_t j = i + 1;
      while (j < n && facets[j].key == facets[i].key) ++j;
      for (std::size_t a = i; a < j; ++a)
        for (std::size_t b = i; b < j; ++b)
          if (facets[a].element != facets[b].element) visit(facets[a].element, facets[b].element);
      i = j;
    }
  };
  forEachPair([&](int a, int) { ++start[a + 1]; });
  for (int e = 0; e < ne; ++e) start[e + 1] += start[e];
  std::vector<int> all(start[ne]), fill(start.begin(), start.end() - 1);
  forEachPair([&](int a, int b) { all[fill[a]++] = b; });
  DualGraph g;
  g.offsets.assign(ne + 1, 0);
  g.neighbors.reserve(all.size());
  for (int e = 0; e < ne; ++e) {
    // Sorted and unique (two elements may share several facets): METIS sees the same graph on
    // every rank.
    auto first = all.begin() + start[e], last = all.begin() + start[e + 1];
    std::sort(first, last);
    g.neighbors.insert(g.neighbors.end(), first, std::unique(first, last));
    g.offsets[e + 1] = static_cast<int>(g.neighbors.size());
  }
  return g;
}

namespace {

// METIS can leave parts empty when there are few elements per part. Each empty part takes one
// element of the currently largest part, the one with the fewest neighbours in it: removing an
// element with a single neighbour cannot disconnect the donor, and anything that does get
// disconnected is split into subdomains later anyway.
void fillEmptyParts(const DualGraph& g, int numParts, std::vector<int>& part) {
  std::vector<int> size(numParts, 0);
  for (int p : part) ++size[p];
  for (int empty = 0; empty < numParts; ++empty) {
    if (size[empty] > 0) continue;
    const int donor = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
    int best = -1, bestDegree = 0;
    for (int e = 0; e < g.numElements(); ++e) {
      if (part[e] != donor) continue;
      int degree = 0;
      for (int k = g.offsets[e]; k < g.offsets[e + 1]; ++k) degree += part[g.neighbors[k]] == donor;
      if (best < 0 || degree < bestDegree) {
        best = e;
        bestDegree = degree;
      }
    }
    part[best] = empty;
    --size[donor];
    ++size[empty];
  }
}

}  // namespace

std::vector<int> partitionElements(const GmshBody& body, int numParts) {
  const int ne = body.numElements();
  if (numParts < 1 || numParts > ne)
    throw std::invalid_argument("partitionElements: body \"" + body.name + "\" has " +
                                std::to_string(ne) + " elements; cannot cut it into " +
                                std::to_string(numParts) + " parts");
  std::vector<int> part(ne, 0);
  if (numParts == 1) return part;

  const DualGraph g = edgeDualGraph(body);
  std::vector<idx_t> xadj(g.offsets.begin(), g.offsets.end());
  std::vector<idx_t> adjncy(g.neighbors.begin(), g.neighbors.end());
  std::vector<idx_t> where(ne, 0);
  idx_t nvtxs = ne, ncon = 1, nparts = numParts, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  // METIS randomizes its matching and refinement: a fixed seed makes every rank (and every run)
  // cut the body identically, which the subdomain numbering across ranks relies on.
  options[METIS_OPTION_SEED] = 20240611;
  // Plain k-way cuts small meshes into many disconnected pieces (each would become a subdomain);
  // contiguous parts avoid that. METIS cannot honour it on a disconnected graph (a body made of
  // separate pieces) and says so on stdout, so it is only asked for on a connected one.
  const std::vector<int> pieces = componentsWithinParts(g, part);
  if (*std::max_element(pieces.begin(), pieces.end()) == 0) options[METIS_OPTION_CONTIG] = 1;
  // An empty adjacency array is legal for METIS but a null pointer from an empty vector is not.
  idx_t dummy = 0;
  const int rc = METIS_PartGraphKway(
      &nvtxs, &ncon, xadj.data(), adjncy.empty() ? &dummy : adjncy.data(), nullptr, nullptr,
      nullptr, &nparts, nullptr, nullptr, options, &objval, where.data());
  if (rc != METIS_OK)
    throw std::runtime_error("partitionElements: METIS_PartGraphKway failed on body \"" +
                             body.name + "\" (code " + std::to_string(rc) + ")");
  for (int e = 0; e < ne; ++e) part[e] = static_cast<int>(where[e]);
  fillEmptyParts(g, numParts, part);
  return part;
}

std::vector<int> componentsWithinParts(const DualGraph& graph, const std::vector<int>& part) {
  const int ne = graph.numElements();
  if (static_cast<int>(part.size()) != ne)
    throw std::invalid_argument("componentsWithinParts: partition size " +
                                std::to_string(part.size()) + " != number of elements " +
                                std::to_string(ne));
  std::vector<int> component(ne, -1);
  std::map<int, int> nextOfPart;
  std::vector<int> stack;
  for (int seed = 0; seed < ne; ++seed) {
    if (component[seed] >= 0) continue;
    const int c = nextOfPart[part[seed]]++;
    component[seed] = c;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      for (int k = graph.offsets[e]; k < graph.offsets[e + 1]; ++k) {
        const int n = graph.neighbors[k];
        if (component[n] < 0 && part[n] == part[e]) {
          component[n] = c;
          stack.push_back(n);
        }
      }
    }
  }
  return component;
}

BodyPartition splitIntoSubdomains(const GmshMesh& mesh, const GmshBody& body,
                                  const std::vector<int>& part, int numParts, int firstId) {
  const int ne = body.numElements(), npe = body.nodesPerElement();
  if (numParts < 1)
    throw std::invalid_argument("splitIntoSubdomains: numParts = " + std::to_string(numParts));
  if (static_cast<int>(part.size()) != ne)
    throw std::invalid_argument("splitIntoSubdomains: body \"" + body.name + "\" has " +
                                std::to_string(ne) + " elements but the partition " +
                                std::to_string(part.size()) + " entries");
  for (int e = 0; e < ne; ++e)
    if (part[e] < 0 || part[e] >= numParts)
      throw std::invalid_argument("splitIntoSubdomains: element " + std::to_string(e) +
                                  " is in part " + std::to_string(part[e]) + ", not in [0, " +
                                  std::to_string(numParts) + ")");

  const std::vector<int> component = componentsWithinParts(edgeDualGraph(body), part);
  std::vector<int> componentsOfPart(numParts, 0);
  for (int e = 0; e < ne; ++e)
    componentsOfPart[part[e]] = std::max(componentsOfPart[part[e]], component[e] + 1);

  BodyPartition out;
  out.numParts = numParts;
  // Subdomain of each (part, component): parts in order, components in order within a part.
  std::vector<int> firstOfPart(numParts + 1, 0);
  for (int p = 0; p < numParts; ++p) {
    firstOfPart[p + 1] = firstOfPart[p] + componentsOfPart[p];
    if (componentsOfPart[p] == 0) ++out.emptyParts;
    if (componentsOfPart[p] > 1) {
      ++out.splitParts;
      out.extraSubdomains += componentsOfPart[p] - 1;
    }
  }
  out.subdomains.resize(firstOfPart[numParts]);
  for (int p = 0; p < numParts; ++p)
    for (int c = 0; c < componentsOfPart[p]; ++c) {
      UnstructuredSubdomain& s = out.subdomains[firstOfPart[p] + c];
      s.id = firstId + firstOfPart[p] + c;
      s.part = p;
      s.type = body.type;
    }
  for (int e = 0; e < ne; ++e)
    out.subdomains[firstOfPart[part[e]] + component[e]].elements.push_back(e);

  for (UnstructuredSubdomain& s : out.subdomains) {
    for (int e : s.elements)
      for (int a = 0; a < npe; ++a)
        s.globalNode.push_back(body.connectivity[static_cast<std::size_t>(e) * npe + a]);
    std::sort(s.globalNode.begin(), s.globalNode.end());
    s.globalNode.erase(std::unique(s.globalNode.begin(), s.globalNode.end()), s.globalNode.end());
    std::unordered_map<long long, int> local;
    local.reserve(s.globalNode.size());
    const int dim = mesh.dim;
    s.coords.resize(dim * s.globalNode.size());
    for (int i = 0; i < s.numNodes(); ++i) {
      const long long g = s.globalNode[i];
      if (g < 0 || g >= mesh.numNodes())
        throw std::invalid_argument("splitIntoSubdomains: body \"" + body.name +
                                    "\" refers to node " + std::to_string(g) + " outside the mesh");
      local[g] = i;
      for (int c = 0; c < dim; ++c) s.coords[dim * i + c] = mesh.coords[dim * g + c];
    }
    s.connectivity.reserve(s.elements.size() * npe);
    for (int e : s.elements)
      for (int a = 0; a < npe; ++a)
        s.connectivity.push_back(
            local.at(body.connectivity[static_cast<std::size_t>(e) * npe + a]));
  }
  return out;
}

std::vector<int> bisectCoordinates(const GmshMesh& mesh, const GmshBody& body, int numParts) {
  const int ne = body.numElements(), npe = body.nodesPerElement(), dim = mesh.dim;
  if (numParts < 1 || numParts > ne)
    throw std::invalid_argument("bisectCoordinates: body \"" + body.name + "\" has " +
                                std::to_string(ne) + " elements; cannot cut it into " +
                                std::to_string(numParts) + " parts");
  std::vector<double> centre(static_cast<std::size_t>(ne) * 3, 0.0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = body.connectivity[static_cast<std::size_t>(e) * npe + a];
      for (int c = 0; c < dim; ++c) centre[3 * e + c] += mesh.coords[dim * n + c] / npe;
    }
  std::vector<int> order(ne), part(ne, 0);
  for (int e = 0; e < ne; ++e) order[e] = e;
  // Each range of `order` is cut across its longest extent, at the element count that gives
  // each side its share of the parts; ties go by element number, so every rank cuts alike.
  const std::function<void(int, int, int, int)> cut = [&](int begin, int end, int parts,
                                                          int first) {
    if (parts == 1) {
      for (int i = begin; i < end; ++i) part[order[i]] = first;
      return;
    }
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int i = begin; i < end; ++i)
      for (int c = 0; c < dim; ++c) {
        lo[c] = std::min(lo[c], centre[3 * order[i] + c]);
        hi[c] = std::max(hi[c], centre[3 * order[i] + c]);
      }
    int axis = 0;
    for (int c = 1; c < dim; ++c)
      if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
    const int left = parts / 2;
    const int mid = begin + static_cast<int>(static_cast<long long>(end - begin) * left / parts);
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](int a, int b) {
                       const double ca = centre[3 * a + axis], cb = centre[3 * b + axis];
                       return ca != cb ? ca < cb : a < b;
                     });
    cut(begin, mid, left, first);
    cut(mid, end, parts - left, first + left);
  };
  cut(0, ne, numParts, 0);
  return part;
}

BodyPartition partitionBody(const GmshMesh& mesh, const GmshBody& body, int numParts, int firstId,
                            Partitioner partitioner) {
  const std::vector<int> part = partitioner == Partitioner::Metis
                                    ? partitionElements(body, numParts)
                                    : bisectCoordinates(mesh, body, numParts);
  return splitIntoSubdomains(mesh, body, part, numParts, firstId);
}

}  // namespace contact
