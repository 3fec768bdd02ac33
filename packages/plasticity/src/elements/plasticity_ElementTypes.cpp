// The host-side half of the element catalogue: names, code look-ups and the node tables
// (facets, reversal, VTK order) derived from the reference nodes of plasticity_ElementTypes.hpp.
#include "plasticity_ElementTypes.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace plasticity {

namespace {

struct CatalogueRow {
  ElementType type;
  const char* name;      // short name
  const char* longName;  // Gmsh's description
};

// Every type, in the catalogue's order (allElementTypes).
const CatalogueRow kCatalogue[] = {
    {ElementType::Line2, "Line2", "2-node line"},
    {ElementType::Line3, "Line3", "3-node line"},
    {ElementType::Tri3, "Tri3", "3-node triangle"},
    {ElementType::Quad4, "Quad4", "4-node quadrangle"},
    {ElementType::Tri6, "Tri6", "6-node triangle"},
    {ElementType::Quad8, "Quad8", "8-node quadrangle"},
    {ElementType::Quad9, "Quad9", "9-node quadrangle"},
    {ElementType::Tet4, "Tet4", "4-node tetrahedron"},
    {ElementType::Tet10, "Tet10", "10-node tetrahedron"},
    {ElementType::Hex8, "Hex8", "8-node hexahedron"},
    {ElementType::Hex20, "Hex20", "20-node hexahedron"},
    {ElementType::Hex27, "Hex27", "27-node hexahedron"},
};

const CatalogueRow* rowOf(ElementType t) {
  for (const CatalogueRow& r : kCatalogue)
    if (r.type == t) return &r;
  return nullptr;
}

// Where VTK numbers the nodes otherwise than Gmsh. Gmsh's Tet10 has the midside nodes of edges
// 3-2 and 3-1 at 8 and 9, VTK's quadratic tetra those of 1-3 and 2-3. Gmsh's Hex20/Hex27 number
// the edges 0-1, 0-3, 0-4, 1-2, 1-5, 2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7 and the faces z-, y-, x-,
// x+, y+, z+; VTK's quadratic and triquadratic hexahedra the edges 0-1, 1-2, 2-3, 3-0, 4-5,
// 5-6, 6-7, 7-4, 0-4, 1-5, 2-6, 3-7 and the faces x-, x+, y-, y+, z-, z+. Corners and the centre
// agree.
const std::map<ElementType, std::vector<int>>& vtkPermutations() {
  static const std::map<ElementType, std::vector<int>> p{
      {ElementType::Tet10, {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}},
      {ElementType::Hex20, {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}},
      {ElementType::Hex27, {0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
                            19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26}}};
  return p;
}

// Facet corners of the 3D families, counter-clockwise seen from outside the reference element.
const int kTetFacets[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
const int kHexFacets[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}};

std::vector<int> facetCorners(const ElementInfo& info, int facet) {
  if (info.dim == 2) return {facet, (facet + 1) % info.corners};
  if (info.simplex) return std::vector<int>(kTetFacets[facet], kTetFacets[facet] + 3);
  return std::vector<int>(kHexFacets[facet], kHexFacets[facet] + 4);
}

// The local node of t at reference point p (among nodes from..nodes-1).
int nodeAt(ElementType t, const double p[], int from) {
  const ElementInfo info = elementInfo(t);
  for (int k = from; k < info.nodes; ++k) {
    double r[kMaxDim];
    referenceNode(t, k, r);
    double d = 0.0;
    for (int j = 0; j < info.dim; ++j) d += std::abs(r[j] - p[j]);
    if (d < 1e-12) return k;
  }
  throw std::logic_error("facetNodes: no node at a facet's reference point");
}

// Corners, then the midside node of each facet edge (a facet of a quadratic element), then the
// facet's centre when its type has one.
std::vector<int> buildFacetNodes(ElementType t, int facet) {
  const ElementInfo info = elementInfo(t);
  std::vector<int> nodes = facetCorners(info, facet);
  if (info.nodes == info.corners) return nodes;
  const int nfc = static_cast<int>(nodes.size()), dim = info.dim;
  if (dim == 2) {  // Gmsh numbers the midside nodes after the corners, in the order of the edges
    nodes.push_back(info.corners + facet);
    return nodes;
  }
  double centre[kMaxDim] = {0, 0, 0};
  for (int j = 0; j < nfc; ++j) {
    double a[kMaxDim], b[kMaxDim], mid[kMaxDim];
    referenceNode(t, nodes[j], a);
    referenceNode(t, nodes[(j + 1) % nfc], b);
    for (int i = 0; i < dim; ++i) mid[i] = 0.5 * (a[i] + b[i]);
    nodes.push_back(nodeAt(t, mid, info.corners));
    for (int i = 0; i < dim; ++i) centre[i] += a[i] / nfc;
  }
  if (nodesPerElement(info.face) > 2 * nfc) nodes.push_back(nodeAt(t, centre, info.corners));
  return nodes;
}

std::vector<int> buildReversedNodes(ElementType t) {
  const ElementInfo info = elementInfo(t);
  const int nc = info.corners;
  std::vector<int> perm;
  for (int k = 0; k < nc; ++k) perm.push_back((nc - k) % nc);
  if (info.nodes == nc) return perm;
  // Reversed edge j runs from old corner (nc - j) % nc to (nc - j - 1) % nc: old edge nc - j - 1.
  for (int j = 0; j < nc; ++j) perm.push_back(nc + (2 * nc - j - 1) % nc);
  for (int k = 2 * nc; k < info.nodes; ++k) perm.push_back(k);  // the centre
  return perm;
}

}  // namespace

const std::vector<ElementType>& allElementTypes() {
  static const std::vector<ElementType> types = [] {
    std::vector<ElementType> v;
    for (const CatalogueRow& r : kCatalogue) v.push_back(r.type);
    return v;
  }();
  return types;
}

std::string elementTypeName(ElementType t) {
  const CatalogueRow* r = rowOf(t);
  return r ? r->name : "unknown";
}

const char* elementLongName(ElementType t) {
  const CatalogueRow* r = rowOf(t);
  return r ? r->longName : "invalid element type";
}

bool elementTypeOfGmsh(int gmshType, ElementType& t) {
  for (const CatalogueRow& r : kCatalogue)
    if (elementInfo(r.type).gmshType == gmshType) return t = r.type, true;
  return false;
}

bool elementTypeOfVtk(int vtkType, ElementType& t) {
  for (const CatalogueRow& r : kCatalogue)
    if (elementInfo(r.type).vtkType == vtkType) return t = r.type, true;
  return false;
}

const std::vector<int>& facetNodes(ElementType t, int facet) {
  // Built once: the tables are derived from the reference nodes.
  static const std::map<ElementType, std::vector<std::vector<int>>> tables = [] {
    std::map<ElementType, std::vector<std::vector<int>>> m;
    for (ElementType e : allElementTypes())
      if (spatialDimension(e) >= 2)
        for (int f = 0; f < facesPerElement(e); ++f) m[e].push_back(buildFacetNodes(e, f));
    return m;
  }();
  const auto it = tables.find(t);
  if (it == tables.end())
    throw std::invalid_argument("facetNodes: a " + elementTypeName(t) +
                                " is not a 2D or 3D element");
  if (facet < 0 || facet >= static_cast<int>(it->second.size()))
    throw std::out_of_range("facetNodes: no such facet");
  return it->second[facet];
}

const std::vector<int>& reversedNodes(ElementType t) {
  static const std::map<ElementType, std::vector<int>> tables = [] {
    std::map<ElementType, std::vector<int>> m;
    for (ElementType e : allElementTypes())
      if (spatialDimension(e) == 2) m[e] = buildReversedNodes(e);
    return m;
  }();
  const auto it = tables.find(t);
  if (it == tables.end())
    throw std::invalid_argument("reversedNodes: a " + elementTypeName(t) + " is not a 2D element");
  return it->second;
}

const std::vector<int>& vtkNodeOrder(ElementType t) {
  static const std::map<ElementType, std::vector<int>> tables = [] {
    std::map<ElementType, std::vector<int>> m = vtkPermutations();
    for (ElementType e : allElementTypes())
      if (!m.count(e))
        for (int k = 0; k < nodesPerElement(e); ++k) m[e].push_back(k);
    return m;
  }();
  return tables.at(t);
}

}  // namespace plasticity
