#include "contact_ContactMaster.hpp"

#include <algorithm>
#include <stdexcept>

namespace contact {

namespace {

std::vector<int> sortedUnique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

class SegmentMaster : public ContactMaster {
 public:
  SegmentMaster(MasterSurface m, const ContactSearchOptions& o) : m_(std::move(m)), o_(o) {}
  int dimension() const override { return 2; }
  ContactRowsResult rows(const std::vector<double>& coords, const std::vector<int>& slaves,
                         const std::vector<double>& u) const override {
    return computeNodeToSegment(coords, slaves, m_, o_, u);
  }
  std::vector<int> masterNodes() const override { return sortedUnique(m_.segments); }

 private:
  MasterSurface m_;
  ContactSearchOptions o_;
};

class FaceMaster : public ContactMaster {
 public:
  FaceMaster(MasterFaceSurface m, const ContactSearchOptions& o) : m_(std::move(m)), o_(o) {}
  int dimension() const override { return 3; }
  ContactRowsResult rows(const std::vector<double>& coords, const std::vector<int>& slaves,
                         const std::vector<double>& u) const override {
    return computeNodeToFace(coords, slaves, m_, o_, u);
  }
  std::vector<int> masterNodes() const override { return sortedUnique(m_.faces); }

 private:
  MasterFaceSurface m_;
  ContactSearchOptions o_;
};

class ObstacleMaster : public ContactMaster {
 public:
  ObstacleMaster(const RigidObstacle& b, const ContactSearchOptions& o) : b_(b), o_(o) {
    b_.validate();
    validateSearchOptions(o_, "rigid obstacle");
  }
  int dimension() const override { return b_.dim; }
  ContactRowsResult rows(const std::vector<double>& coords, const std::vector<int>& slaves,
                         const std::vector<double>& u) const override {
    return computeObstacleRows(b_, coords, slaves, o_, u);
  }
  std::vector<int> masterNodes() const override { return {}; }

 private:
  RigidObstacle b_;
  ContactSearchOptions o_;
};

}  // namespace

std::unique_ptr<ContactMaster> makeSegmentMaster(MasterSurface master,
                                                 const ContactSearchOptions& options) {
  return std::make_unique<SegmentMaster>(std::move(master), options);
}

std::unique_ptr<ContactMaster> makeFaceMaster(MasterFaceSurface master,
                                              const ContactSearchOptions& options) {
  return std::make_unique<FaceMaster>(std::move(master), options);
}

std::unique_ptr<ContactMaster> makeObstacleMaster(const RigidObstacle& obstacle,
                                                  const ContactSearchOptions& options) {
  return std::make_unique<ObstacleMaster>(obstacle, options);
}

MasterSurface masterSegmentsOfBoundary(const GmshMesh& mesh, const GmshBoundary& g) {
  int body = -1;
  for (int e = 0; e < g.numEdges() && body < 0; ++e) body = g.edgeBody[e];
  if (body < 0)
    throw std::invalid_argument(mesh.source + ": boundary \"" + g.name + "\" is on no body");
  MasterSurface m;
  m.nodesPerSegment = g.nodesPerEdge;
  m.segments = g.edges;
  const GmshBody& b = mesh.bodies[body];
  orientSegmentsByElements(m, mesh.coords, b.type, b.connectivity);
  return m;
}

std::unique_ptr<ContactMaster> makeMeshContactMaster(const GmshMesh& mesh,
                                                     const std::string& boundary,
                                                     const ContactSearchOptions& options) {
  const GmshBoundary& g = mesh.boundary(boundary);
  if (mesh.dim == 3) return makeFaceMaster(masterFacesOfBoundary(mesh, g), options);
  return makeSegmentMaster(masterSegmentsOfBoundary(mesh, g), options);
}

}  // namespace contact
