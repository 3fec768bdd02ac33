// The reference paper's two cylinders as a full model for Cattaneo-Mindlin partial slip (no
// symmetry plane: a tangential load breaks it). The cylinder is the lower half of a disc of
// radius R centred at (0, R), its flat top edge "load" at y = R; it touches the block
// (-W, W) x (-D, 0) at the origin. The block's top is one straight curve without a point at the
// origin, so the two bodies share no node. Mesh size: `fine` within `near` of the contact point,
// growing to `coarse` at distance `far` (as examples/two_cylinders.geo).
R = 1.0;
W = 2.0;
D = 2.0;
// (each may be set before this file is included: tests/meshes/cattaneo_cylinders_coarse.geo)
If (!Exists(fine))
  fine = 0.002;
EndIf
If (!Exists(coarse))
  coarse = 0.25;
EndIf
If (!Exists(near))
  near = 0.06;
EndIf
If (!Exists(far))
  far = 1.0;
EndIf

Point(1) = {0, R, 0, coarse};   // centre
Point(2) = {-R, R, 0, coarse};
Point(3) = {0, 0, 0, coarse};   // the cylinder's contact point
Point(4) = {R, R, 0, coarse};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

Point(11) = {-W, -D, 0, coarse};
Point(12) = {W, -D, 0, coarse};
Point(13) = {W, 0, 0, coarse};
Point(14) = {-W, 0, 0, coarse};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

Field[1] = Distance;
Field[1].PointsList = {3};
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
Physical Curve("cylinder_contact") = {1, 2};
Physical Curve("load") = {3};
Physical Curve("block_contact") = {13};
Physical Curve("fixed") = {11};
Physical Curve("block_sides") = {12, 14};
