// The reference paper's two-cylinder problem as a half model (x >= 0, symmetry on x = 0): a
// cylinder of radius R resting on a flat block (R2 = infinity), plane strain. The cylinder is a
// quarter disc centred at (0, R), loaded on its top edge y = R; it touches the block's top y = 0
// at the origin. The two bodies have separate points at the origin, so they share no node.
// Mesh size: `fine` within `near` of the contact point, growing to `coarse` at distance `far`.
R = 1.0;
W = 2.0;  // block width (half model)
D = 2.0;  // block depth
If (!Exists(fine))
  fine = 0.002;
EndIf
coarse = 0.25;
near = 0.06;
far = 1.0;

Point(1) = {0, R, 0, coarse};  // cylinder centre
Point(2) = {0, 0, 0, coarse};  // cylinder's contact point
Point(3) = {R, R, 0, coarse};
Circle(1) = {2, 1, 3};
Line(2) = {3, 1};
Line(3) = {1, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

Point(11) = {0, 0, 0, coarse};  // block's corner at the contact point
Point(12) = {0, -D, 0, coarse};
Point(13) = {W, -D, 0, coarse};
Point(14) = {W, 0, 0, coarse};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

Field[1] = Distance;
Field[1].PointsList = {2, 11};
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

Physical Surface("cylinder") = {1};
Physical Surface("block") = {2};
Physical Curve("cylinder_contact") = {1};
Physical Curve("load") = {2};
Physical Curve("cylinder_symmetry") = {3};
Physical Curve("block_contact") = {14};
Physical Curve("block_symmetry") = {11};
Physical Curve("fixed") = {12};
