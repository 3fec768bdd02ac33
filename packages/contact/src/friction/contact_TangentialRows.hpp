#pragma once
// Tangential contact rows B_T beside the non-penetration rows B_N (friction). For a slave node
// with the normal row
//     -(n . u_s) + sum_a N_a (n . u_a) <= gap,
// each tangent t of the master at the closest point gives the row
//     -(t . u_s) + sum_a N_a (t . u_a),
// minus the relative tangential displacement (slip) of the slave node along t: the same nodes,
// the normal replaced by the tangent. Its multiplier is the tangential force on the slave node
// along t (B^T lambda acts on the slave as t lambda_T, as the normal row's multiplier pushes it
// along n), bounded by the friction law (Tresca: |lambda_T| <= g).
//
// One code path for 2D and 3D: the tangents are an orthonormal basis of the plane normal to n,
// dim - 1 of them (2D: t = (-n_y, n_x), the direction from a to b of the master segment, whose
// outward normal is t turned clockwise; 3D: two tangents, t1 x t2 = n, a smooth function of n
// for n_z >= 0 and for n_z < 0 that does not flip with rounding). In 3D the two rows of a node
// form a disc (InequalityRow::disc = 1, 2): |lambda_T| <= g on the tangential force vector. The
// row's coefficient of a node's component c is its weight s (-1 for the slave, N_a for a master
// node, read back from the normal row as s = sum_c coef_c n_c) times t_c, so a rigid obstacle's
// rows (slave entries only) are handled alike.
#include <array>
#include <functional>
#include <vector>

#include "contact_ContactRows.hpp"

namespace contact {

// The dim - 1 unit tangents orthogonal to the unit normal n (z ignored in 2D).
std::vector<std::array<double, 3>> tangentBasis(const std::array<double, 3>& n, int dim);

// The tangential rows of a normal row: dim - 1 rows, each with `normal` holding its tangent t,
// `gap` = 0 (the slip reference is the caller's: B_T u <= c_T is not a constraint but the
// argument of the friction bound) and the same entries (nodes, components) as the normal row.
// Throws std::invalid_argument when the row's entries are not dim components per node.
std::vector<ContactRow> tangentialRows(const ContactRow& normalRow, int dim);

// Whether a mesh node's component is held by a Dirichlet condition (Fixed, Symmetry or
// Prescribed boundaries).
using HeldComponent = std::function<bool(int node, int component)>;

// The tangential rows that friction adds beside a normal row: tangentialRows' rows, less the
// directions in which the pair cannot slide because the row's nodes are held there: the slave
// node, and the master nodes it is projected between but for at most 5 % of the row's weight
// (the deformed normal tilts the closest point a little off a held master edge). On a symmetry
// plane y = 0 that cuts the contact (a half model) both sides have u_y = 0: the tangential row
// along y would be a combination of the symmetry rows, which makes the dual Hessian singular
// with a disc on that direction, and its multiplier is the symmetry's reaction, not friction
// (zero by symmetry). Each held direction e_c that is not along n (|e_c - (e_c . n) n| > 0.1,
// orthogonalized against the others) removes one tangent: 3D keeps t = n x e_c / |n x e_c|
// (one row, a box) or none; 2D keeps its tangent or none. Where nothing is held, the rows are
// tangentialRows' bit for bit.
// mirrored (optional): the components a Symmetry boundary holds. A slave node on a symmetry
// plane normal to e_c loses the tangent along e_c whatever the master's weights: by symmetry the
// friction traction normal to the plane vanishes there, and the master side lies on the plane
// too. Dual mortar rows put 5-6 % of their weight on off-plane master nodes (signed dual-basis
// weights), above the 5 % rule, and the row left was within 5 % of the symmetry rows' span: its
// scaling group of B B^T nearly singular, the preconditioner's eigenvalue there 100 times the
// others' (docs/friction.md, "Directions held on both sides").
std::vector<ContactRow> frictionTangentialRows(const ContactRow& normalRow, int dim,
                                               const HeldComponent& held,
                                               const HeldComponent& mirrored = nullptr);

// Sum of the row's coefficients times the displacement (dim per mesh node): B_T,i u.
double applyRow(const ContactRow& row, int dim, const std::vector<double>& displacement);

}  // namespace contact
