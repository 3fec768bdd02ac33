// Recovered fields: smoother estimates of the contact pressure and of the von Mises stress than
// the raw nodal values, for the elements whose raw values scatter (linear tetrahedra).
//
// Why: on an unstructured Tet4 mesh every node's multiplier follows the stiffness of the
// irregular constant-strain elements around it, so the nodal pressures scatter around the exact
// profile (2-2.5 % RMS of Hertz's p0 at a/h = 12-22) and their largest lands 2-5 % above p0,
// although a least-squares fit of Hertz's profile to the same nodes is within 0.8 %
// (docs/mortar_contact.md, "Recovered pressure and stress"). The same holds for the constant stress
// of a Tet4 element: the largest element value overshoots the peak of a smooth field. The raw
// values stay the reported ones (p_max, max_von_mises, the CSV's pressure); these are added.
#pragma once

#include <array>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "plasticity_Elements.hpp"
#include "tfeti_Types.hpp"

namespace contact {

// Per point i: the value at x[i] of the polynomial of degree[i] (1 or 2) in the tangential
// coordinates (in the plane through x[i] normal to normal[i]; in 2D along the line) fitted by
// least squares to the values of the points patch[i] (i itself included). Reproduces a
// polynomial of that degree exactly. Where the patch does not determine the polynomial (too
// few points, or all on one line in 3D) the next lower degree is tried, and below degree 1 the
// point keeps its own value.
std::vector<double> patchRecovery(const std::vector<std::array<double, 3>>& x,
                                  const std::vector<std::array<double, 3>>& normal,
                                  const std::vector<double>& value,
                                  const std::vector<std::vector<int>>& patch, int dim,
                                  const std::vector<int>& degree);

// The mirror images of `point` across the planes x_c = onPlanes[c], c in components (each an
// axis: a Symmetry boundary holds that displacement component), under every combination of
// the reflections, without the point itself. A point within tol of a plane is its own image
// there: it adds no image across it.
std::vector<std::array<double, 3>> mirrorImages(const std::array<double, 3>& onPlanes,
                                                const std::vector<int>& components,
                                                const std::array<double, 3>& point, double tol);

// Sets ContactNode::pressureRecovered of every node (contactNodes' of `problem`): the
// patch recovery (linear on linear slave facets, quadratic on quadratic ones) of the pressures over
// the node and the nodes sharing a facet of the pair's slave boundary with it that have a row in
// the pair (open ones with their zero, so that the fit near the contact's edge follows the
// pressure's drop to zero), clipped at zero; zero where the node's own pressure is zero (an open
// row stays open). A node on a symmetry plane (ElasticContactProblem::mirroredComponents) takes its
// neighbours' mirror images across the plane into its patch too, as the whole body's ring would
// hold them.
void recoverContactPressures(std::vector<ContactNode>& nodes, const ElasticContactProblem& problem);

double maxRecoveredPressure(const std::vector<ContactNode>& nodes);

// The largest von Mises stress of the nodal stress tensors averaged over every element of one
// body sharing the node, in all subdomains (so the figure does not depend on the decomposition;
// a node two bodies share averages each body's elements apart); stresses: one field per local
// subdomain of `problem`. Every rank gets the value.
double maxNodalVonMises(const tfeti::Comm& comm, const ElasticContactProblem& problem,
                        const std::vector<plasticity::StressField>& stresses);

}  // namespace contact
