// The unstructured Tet4 variant of hertz_sphere_elastic.geo (which is now structured Hex8 and
// ignores Mesh size factor): used by the plastic sphere example and its CI copies, where a few
// hundred nodes keep a nonlinear run short.
// Hertz's point contact, quarter model: the lower half of an elastic sphere (radius R = 1 m,
// centre (0, 0, R)) on an elastic block (0, B) x (0, B) x (-H, 0); they touch at the origin.
// Symmetry planes x = 0 and y = 0; the sphere's flat cut z = R carries the load, the block's
// bottom is fixed. Mesh sizes: a MathEval field, hMin within the distance rZone of the contact
// point, then growing linearly with the distance up to hMax (Mesh.MeshSizeFactor scales the
// sizes). For F = 5e5 N, E = 2e11 Pa, nu = 0.3 Hertz's contact radius is a = 15.05 mm: hMin = 2
// mm is about a/7.5, and the zone of that size covers the contact area with a margin.
SetFactory("OpenCASCADE");
R = 1.0;
B = 1.0;
H = 1.0;
hMin = 0.002;   // within rZone of the contact point
rZone = 0.02;   // 1.33 a
grow = 0.3;     // size increase per unit distance beyond rZone
hMax = 0.25;
Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {0, 0, -H, B, B, H};
eps = 1e-6;
sphereTop[] = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
sphereX[] = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
sphereY[] = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps};
sphereAll[] = Boundary{ Volume{3}; };
blockTop[] = Surface In BoundingBox{-eps, -eps, -eps, B + eps, B + eps, eps};
blockBottom[] = Surface In BoundingBox{-eps, -eps, -H - eps, B + eps, B + eps, -H + eps};
blockX[] = Surface In BoundingBox{-eps, -eps, -H - eps, eps, B + eps, eps};
blockY[] = Surface In BoundingBox{-eps, -eps, -H - eps, B + eps, eps, eps};
Physical Volume("sphere") = {3};
Physical Volume("block") = {4};
sphereContact[] = sphereAll[];
sphereContact[] -= {sphereTop[], sphereX[], sphereY[]};
Physical Surface("sphere_contact") = {sphereContact[]};
Physical Surface("sphere_top") = {sphereTop[]};
Physical Surface("block_contact") = {blockTop[]};
Physical Surface("block_bottom") = {blockBottom[]};
Physical Surface("symmetry_x") = {sphereX[], blockX[]};
Physical Surface("symmetry_y") = {sphereY[], blockY[]};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g * Max(0, Sqrt(x * x + y * y + z * z) - %g))", hMax, hMin,
                     grow, rZone);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
