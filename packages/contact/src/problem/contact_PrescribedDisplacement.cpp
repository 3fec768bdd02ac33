#include "contact_PrescribedDisplacement.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <set>
#include <sstream>
#include <stdexcept>

#include "tfeti_StrictParameters.hpp"

namespace contact {

using Teuchos::Array;

tfeti::strict::Validator componentsValidator() {
  const auto components = Teuchos::rcp(
      new tfeti::strict::NumberValidator(tfeti::strict::NumberValidator::Kind::IntArray));
  components->atLeast(0).atMost(2);
  return components;
}

void addPrescribedDisplacementParameters(Teuchos::ParameterList& list) {
  list.set("Prescribed boundaries", Array<std::string>(),
           "boundaries where one component of u is prescribed (non-zero values allowed); one "
           "entry per prescribed component, a name may repeat");
  list.set("Prescribed components", Array<int>(),
           "the prescribed component (0: x, 1: y, 2: z; 0 for the scalar problem) of each "
           "Prescribed boundaries entry",
           componentsValidator());
  list.set("Prescribed displacements", Array<double>(),
           "the prescribed value of each Prescribed boundaries entry, in m (the unknown's unit "
           "for the scalar problem)",
           tfeti::strict::doubles(0));
}

std::vector<PrescribedDisplacement> prescribedDisplacements(const Teuchos::ParameterList& list,
                                                            const std::string& where) {
  const auto names = list.get<Array<std::string>>("Prescribed boundaries");
  const auto components = list.get<Array<int>>("Prescribed components");
  const auto values = list.get<Array<double>>("Prescribed displacements");
  if (components.size() != names.size() || values.size() != names.size())
    throw std::invalid_argument(
        where +
        ": \"Prescribed boundaries\", \"Prescribed components\" and \"Prescribed "
        "displacements\" need one entry per prescribed component (got " +
        std::to_string(names.size()) + ", " + std::to_string(components.size()) + " and " +
        std::to_string(values.size()) + ")");
  std::vector<PrescribedDisplacement> out;
  for (int k = 0; k < static_cast<int>(names.size()); ++k)
    out.push_back({names[k], components[k], values[k], {}});
  return out;
}

std::string describePrescribed(const PrescribedDisplacement& p, int dofsPerNode) {
  std::ostringstream s;
  s << (dofsPerNode == 1 ? std::string("u") : std::string("u_") + "xyz"[p.component % 3]) << " = "
    << p.value;
  return s.str();
}

PrescribedValues prescribedValues(const std::vector<PrescribedDisplacement>& prescribed,
                                  int dofsPerNode, const BoundaryNodes& nodesOf,
                                  const std::vector<std::string>& fixed,
                                  const std::vector<std::pair<std::string, int>>& symmetry) {
  const std::string valid = dofsPerNode == 1   ? "0 (the scalar problem has one component)"
                            : dofsPerNode == 2 ? "0 (x) or 1 (y) (a 2D problem)"
                                               : "0 (x), 1 (y) or 2 (z) (a 3D problem)";
  // Where fixed and symmetry conditions hold a component at zero, and by which boundary.
  std::map<std::pair<long long, int>, std::string> zero;
  for (const auto& name : fixed)
    for (long long n : nodesOf(name))
      for (int c = 0; c < dofsPerNode; ++c)
        zero.insert({{n, c}, "fixed boundary \"" + name + "\""});
  for (const auto& [name, c] : symmetry)
    for (long long n : nodesOf(name)) zero.insert({{n, c}, "symmetry boundary \"" + name + "\""});

  PrescribedValues values;
  std::map<std::pair<long long, int>, std::size_t> from;  // which entry set a value
  for (std::size_t k = 0; k < prescribed.size(); ++k) {
    const PrescribedDisplacement& p = prescribed[k];
    if (p.component < 0 || p.component >= dofsPerNode)
      throw std::invalid_argument("Prescribed components: " + std::to_string(p.component) +
                                  " for boundary \"" + p.boundary + "\" is not " + valid);
    for (long long n : nodesOf(p.boundary)) {
      const std::pair<long long, int> key{n, p.component};
      const auto z = zero.find(key);
      if (z != zero.end()) {
        if (p.value != 0.0)
          throw std::invalid_argument("Prescribed boundaries: \"" + p.boundary + "\" prescribes " +
                                      describePrescribed(p, dofsPerNode) + " at a node of the " +
                                      z->second + ", which holds that component at 0");
        continue;  // already held at zero
      }
      const auto [it, added] = values.insert({key, {p.value, p.ramp}});
      const LoadRamp& r = it->second.ramp;
      if (!added && it->second.value == p.value && (r.start != p.ramp.start || r.end != p.ramp.end))
        throw std::invalid_argument("Prescribed ramps: \"" + p.boundary + "\" (" +
                                    describePrescribed(p, dofsPerNode) + ") and \"" +
                                    prescribed[from[key]].boundary +
                                    "\" meet at a node with different ramps of the same component");
      if (!added && it->second.value != p.value)
        throw std::invalid_argument("Prescribed boundaries: \"" + p.boundary + "\" (" +
                                    describePrescribed(p, dofsPerNode) + ") and \"" +
                                    prescribed[from[key]].boundary + "\" (" +
                                    describePrescribed(prescribed[from[key]], dofsPerNode) +
                                    ") meet at a node with different values of the same component");
      if (added) from[key] = k;
    }
  }
  return values;
}

std::vector<tfeti::EqualityRow> prescribedDisplacementRows(
    const std::vector<tfeti::SubdomainData>& local, const PrescribedValues& values,
    double loadFactor, const std::vector<std::vector<double>>& current) {
  if (!current.empty() && current.size() != local.size())
    throw std::invalid_argument("prescribedDisplacementRows: " + std::to_string(current.size()) +
                                " displacement vectors for " + std::to_string(local.size()) +
                                " local subdomains");
  std::vector<tfeti::EqualityRow> rows;
  if (values.empty()) return rows;
  for (std::size_t i = 0; i < local.size(); ++i) {
    const tfeti::SubdomainData& sd = local[i];
    const int dpn = sd.dofsPerNode;
    for (int n = 0; n < sd.mesh.numNodes(); ++n)
      for (int c = 0; c < dpn; ++c) {
        const auto it = values.find({sd.mesh.globalNode[n], c});
        if (it == values.end()) continue;
        const int dof = dpn * n + c;
        const double u0 = current.empty() ? 0.0 : current[i].at(dof);
        rows.push_back({{{sd.mesh.id, dof, 1.0}}, it->second.at(loadFactor) - u0});
      }
  }
  return rows;
}

std::vector<double> prescribedReactions(const tfeti::FetiSolver& solver,
                                        const std::vector<PrescribedDisplacement>& prescribed,
                                        const BoundaryNodes& nodesOf) {
  const std::vector<std::vector<double>> forces = solver.multiplierForces();
  std::vector<double> mine(prescribed.size(), 0.0), all(prescribed.size(), 0.0);
  for (std::size_t k = 0; k < prescribed.size(); ++k) {
    const std::vector<long long> list = nodesOf(prescribed[k].boundary);
    const std::set<long long> nodes(list.begin(), list.end());
    for (std::size_t i = 0; i < solver.data().size(); ++i) {
      const auto& sd = solver.data()[i];
      for (int n = 0; n < sd.mesh.numNodes(); ++n)
        if (nodes.count(sd.mesh.globalNode[n]))
          mine[k] -= forces[i][sd.dofsPerNode * n + prescribed[k].component];
    }
  }
  if (!mine.empty())
    Teuchos::reduceAll(*solver.comm(), Teuchos::REDUCE_SUM, static_cast<int>(mine.size()),
                       mine.data(), all.data());
  return all;
}

Json prescribedSummary(const tfeti::FetiSolver& solver,
                       const std::vector<PrescribedDisplacement>& prescribed,
                       const BoundaryNodes& nodesOf) {
  const std::vector<double> reactions = prescribedReactions(solver, prescribed, nodesOf);
  Json list = Json::array();
  for (std::size_t k = 0; k < reactions.size(); ++k) {
    Json r = Json::object();
    r["boundary"] = prescribed[k].boundary;
    r["component"] = prescribed[k].component;
    r["value"] = prescribed[k].value;
    if (!prescribed[k].ramp.isDefault()) {
      Json ramp = Json::array();
      ramp.push(prescribed[k].ramp.start);
      ramp.push(prescribed[k].ramp.end);
      r["ramp"] = std::move(ramp);
    }
    r["reaction"] = reactions[k];
    list.push(std::move(r));
  }
  return list;
}

}  // namespace contact
