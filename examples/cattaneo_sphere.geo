// Cattaneo-Mindlin's sphere, half model: the lower half of an elastic sphere (radius R = 1 m,
// centre (0, 0, R)) cut at y = 0, on an elastic block (-B, B) x (0, B) x (-H, 0); they touch at
// the origin. One symmetry plane y = 0 (the tangential load is along x, so x = 0 is no symmetry
// plane). The sphere's flat cut z = R ("sphere_top") is the rigid loading plate, the block's
// bottom is fixed. Unstructured Tet4; mesh sizes: a MathEval field, hMin within rZone of the
// contact point, then growing linearly with the distance up to hMax (Mesh size factor scales
// them). For the half load P = 2e6 N (full 4e6 N), E = 2e11 Pa, nu = 0.3 Hertz's contact
// radius is a = 30.1 mm: hMin = 3 mm is about a/10.
SetFactory("OpenCASCADE");
R = 1.0;
B = 1.0;
H = 1.0;
hMin = 0.003;
rZone = 0.04;
grow = 0.3;
hMax = 0.25;
Sphere(1) = {0, 0, R, R};
Box(2) = {-R, 0, 0, 2 * R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {-B, 0, -H, 2 * B, B, H};
eps = 1e-6;
sphereTop[] = Surface In BoundingBox{-R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
sphereY[] = Surface In BoundingBox{-R - eps, -eps, -eps, R + eps, eps, R + eps};
sphereAll[] = Boundary{ Volume{3}; };
blockTop[] = Surface In BoundingBox{-B - eps, -eps, -eps, B + eps, B + eps, eps};
blockBottom[] = Surface In BoundingBox{-B - eps, -eps, -H - eps, B + eps, B + eps, -H + eps};
blockY[] = Surface In BoundingBox{-B - eps, -eps, -H - eps, B + eps, eps, eps};
Physical Volume("sphere") = {3};
Physical Volume("block") = {4};
sphereContact[] = sphereAll[];
sphereContact[] -= {sphereTop[], sphereY[]};
Physical Surface("sphere_contact") = {sphereContact[]};
Physical Surface("sphere_top") = {sphereTop[]};
Physical Surface("block_contact") = {blockTop[]};
Physical Surface("block_bottom") = {blockBottom[]};
Physical Surface("symmetry_y") = {sphereY[], blockY[]};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g * Max(0, Sqrt(x * x + y * y + z * z) - %g))", hMax, hMin,
                     grow, rZone);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
