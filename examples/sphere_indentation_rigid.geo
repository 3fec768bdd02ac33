// Indentation of an elastic-plastic block by a rigid sphere, quarter model: the block
// (0, B) x (0, B) x (-H, 0) with symmetry planes x = 0 and y = 0, its bottom z = -H fixed and
// its top z = 0 the contact surface; the sphere (radius 1 m) is analytic (a Rigid obstacle in
// the input), touching the top at the origin. Mesh sizes: hMin within rZone of the origin, then
// growing linearly with the distance up to hMax (Mesh.MeshSizeFactor scales them). For the
// indentation depth of examples/sphere_indentation_rigid.xml (0.4 mm) the elastic contact radius
// would be sqrt(R d) = 20 mm: hMin = 3 mm is about a/7, rZone covers the contact zone.
SetFactory("OpenCASCADE");
B = 0.5;
H = 0.5;
hMin = 0.003;
rZone = 0.03;
grow = 0.4;
hMax = 0.15;
Box(1) = {0, 0, -H, B, B, H};
eps = 1e-6;
top[] = Surface In BoundingBox{-eps, -eps, -eps, B + eps, B + eps, eps};
bottom[] = Surface In BoundingBox{-eps, -eps, -H - eps, B + eps, B + eps, -H + eps};
sx[] = Surface In BoundingBox{-eps, -eps, -H - eps, eps, B + eps, eps};
sy[] = Surface In BoundingBox{-eps, -eps, -H - eps, B + eps, eps, eps};
Physical Volume("block") = {1};
Physical Surface("block_contact") = {top[]};
Physical Surface("block_bottom") = {bottom[]};
Physical Surface("symmetry_x") = {sx[]};
Physical Surface("symmetry_y") = {sy[]};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g * Max(0, Sqrt(x * x + y * y + z * z) - %g))", hMax, hMin,
                     grow, rZone);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
