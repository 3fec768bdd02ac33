// Pin in a hole, plane strain, as a half model (x >= 0, symmetry on x = 0). The plate is an
// 8 m x 8 m square centred at the origin with a hole of radius 1 at the origin, clamped on its
// outer edges x = 4, y = +-4. The pin is a disc of radius Rp < 1 centred at (0, -(1 - Rp)): it
// touches the hole at the single point (0, -1) only, where the two bodies have separate points
// (they share no node). The pin is pushed down (-y) by a body force, so the contact spreads from
// the bottom point (0, -1) along the lower part of the hole: a Hertz-like half-width of about
// 0.12 m for Rp = 0.9, an arc of tens of degrees for the conforming Rp = 0.99.
// Each circle is split into a lower arc, within `arc` degrees of the bottom point, and the rest;
// the mesh size is `fine` within `near` of the two lower arcs, growing to `coarse` at distance
// `far`. Set Rp (and any mesh parameter) before including this file: pin_hole_0.9.geo,
// pin_hole_0.99.geo.
If (!Exists(Rp))
  Rp = 0.9;
EndIf
If (!Exists(fine))
  fine = 0.01;
EndIf
If (!Exists(coarse))
  coarse = 0.3;
EndIf
If (!Exists(near))
  near = 0.1;  // deep enough for the stress peak below the contact (~0.8 half-widths deep)
EndIf
If (!Exists(far))
  far = 1.0;
EndIf
If (!Exists(arc))
  arc = 50;  // degrees from the bottom point: the refined lower arcs
EndIf
L = 4.0;  // half-size of the plate
R = 1.0;  // hole radius
a = arc * Pi / 180;
yc = -(R - Rp);  // pin centre

// Plate: the outer edges, then the hole as a lower arc (bottom point to angle `arc`) and the rest.
Point(1) = {0, 0, 0, coarse};  // hole centre
Point(2) = {0, -R, 0, coarse};  // hole's bottom point: the first contact
Point(3) = {R * Sin(a), -R * Cos(a), 0, coarse};
Point(4) = {0, R, 0, coarse};
Point(5) = {0, L, 0, coarse};
Point(6) = {L, L, 0, coarse};
Point(7) = {L, -L, 0, coarse};
Point(8) = {0, -L, 0, coarse};
Circle(1) = {2, 1, 3};  // lower arc of the hole
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Line(4) = {5, 6};
Line(5) = {6, 7};
Line(6) = {7, 8};
Line(7) = {8, 2};
Curve Loop(1) = {7, 1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// Pin: a half disc with its own bottom point at (0, -R).
Point(11) = {0, yc, 0, coarse};  // pin centre
Point(12) = {0, yc - Rp, 0, coarse};  // pin's bottom point, = (0, -R)
Point(13) = {Rp * Sin(a), yc - Rp * Cos(a), 0, coarse};
Point(14) = {0, yc + Rp, 0, coarse};
Circle(11) = {12, 11, 13};  // lower arc of the pin
Circle(12) = {13, 11, 14};
Line(13) = {14, 12};
Curve Loop(2) = {11, 12, 13};
Plane Surface(2) = {2};

Field[1] = Distance;
Field[1].CurvesList = {1, 11};
Field[1].NumPointsPerCurve = 400;  // "Sampling" in later Gmsh, which still accepts this name
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = fine;
Field[2].SizeMax = coarse;
Field[2].DistMin = near;
Field[2].DistMax = far;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Surface("plate") = {1};
Physical Surface("pin") = {2};
Physical Curve("plate_fixed") = {4, 5, 6};
Physical Curve("plate_symmetry") = {3, 7};
Physical Curve("hole") = {1, 2};
Physical Curve("pin_surface") = {11, 12};
Physical Curve("pin_symmetry") = {13};
