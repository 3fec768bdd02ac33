// Two copies of tests/meshes/cattaneo_cylinders_coarse.geo side by side, 10 m apart along x, for
// friction on several contact pairs (tests/inputs/nl_cattaneo_two_pairs.xml): the first copy's
// names as in examples/cattaneo_cylinders.geo, the second's with the suffix 2. The copies share
// the Fixed boundary "fixed" only, so the two contact problems are independent and each pair must
// give what its copy alone gives.
R = 1.0;
W = 2.0;
D = 2.0;
S = 10.0;
fine = 0.002;
near = 0.025;
far = 0.5;
coarse = 0.5;

For copy In {0:1}
  x0 = copy * S;
  o = 100 * copy;
  Point(o + 1) = {x0, R, 0, coarse};
  Point(o + 2) = {x0 - R, R, 0, coarse};
  Point(o + 3) = {x0, 0, 0, coarse};
  Point(o + 4) = {x0 + R, R, 0, coarse};
  Circle(o + 1) = {o + 2, o + 1, o + 3};
  Circle(o + 2) = {o + 3, o + 1, o + 4};
  Line(o + 3) = {o + 4, o + 2};
  Curve Loop(o + 1) = {o + 1, o + 2, o + 3};
  Plane Surface(o + 1) = {o + 1};
  Point(o + 11) = {x0 - W, -D, 0, coarse};
  Point(o + 12) = {x0 + W, -D, 0, coarse};
  Point(o + 13) = {x0 + W, 0, 0, coarse};
  Point(o + 14) = {x0 - W, 0, 0, coarse};
  Line(o + 11) = {o + 11, o + 12};
  Line(o + 12) = {o + 12, o + 13};
  Line(o + 13) = {o + 13, o + 14};
  Line(o + 14) = {o + 14, o + 11};
  Curve Loop(o + 2) = {o + 11, o + 12, o + 13, o + 14};
  Plane Surface(o + 2) = {o + 2};
EndFor

// The second copy's mesh is the first's translated (a periodic mesh), so that the two contact
// problems are the same discrete problem.
Periodic Surface{101} = {1} Translate{S, 0, 0};
Periodic Surface{102} = {2} Translate{S, 0, 0};

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
Physical Surface("cylinder2") = {101};
Physical Surface("block2") = {102};
Physical Curve("cylinder2_contact") = {101, 102};
Physical Curve("load2") = {103};
Physical Curve("block2_contact") = {113};
Physical Curve("fixed") = {11, 111};
