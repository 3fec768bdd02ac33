// Several contact pairs in 2D (tests/inputs/disc_between_blocks.xml): a disc of radius R centred
// at the origin between two blocks, half model (x >= 0, symmetry on x = 0), plane strain. The
// half disc touches the lower block's top y = -R at (0, -R) and the upper block's bottom y = R
// at (0, R); each body has its own points there, so they share no node. The disc's arc is one
// boundary, "disc_contact", the slave of both pairs. Mesh size: `fine` within `near` of the
// contact points, growing to `coarse` at distance `far`.
R = 1.0;
W = 1.5;  // block width (half model)
D = 0.6;  // block depth
fine = 0.004;
coarse = 0.2;
near = 0.05;
far = 0.8;

Point(1) = {0, 0, 0, coarse};   // disc centre
Point(2) = {0, -R, 0, coarse};  // disc's lower contact point
Point(3) = {R, 0, 0, coarse};
Point(4) = {0, R, 0, coarse};   // disc's upper contact point
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 1};
Line(4) = {1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Point(11) = {0, -R, 0, coarse};  // lower block's corner at the contact point
Point(12) = {0, -R - D, 0, coarse};
Point(13) = {W, -R - D, 0, coarse};
Point(14) = {W, -R, 0, coarse};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

Point(21) = {0, R, 0, coarse};  // upper block's corner at the contact point
Point(22) = {W, R, 0, coarse};
Point(23) = {W, R + D, 0, coarse};
Point(24) = {0, R + D, 0, coarse};
Line(21) = {21, 22};
Line(22) = {22, 23};
Line(23) = {23, 24};
Line(24) = {24, 21};
Curve Loop(3) = {21, 22, 23, 24};
Plane Surface(3) = {3};

Field[1] = Distance;
Field[1].PointsList = {2, 4, 11, 21};
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

Physical Surface("disc") = {1};
Physical Surface("lower_block") = {2};
Physical Surface("upper_block") = {3};
Physical Curve("disc_contact") = {1, 2};
Physical Curve("lower_contact") = {14};
Physical Curve("upper_contact") = {21};
Physical Curve("fixed") = {12};
Physical Curve("load") = {23};
Physical Curve("symmetry") = {3, 4, 11, 24};
