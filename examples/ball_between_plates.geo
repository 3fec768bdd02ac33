// An elastic ball squeezed between two elastic plates, quarter model (symmetry planes x = 0 and
// y = 0): the ball (radius R, centre at the origin) touches the lower plate (0, B) x (0, B) x
// (-R - T, -R) at its south pole and the upper plate (0, B) x (0, B) x (R, R + T) at its north
// pole. One curved surface of the ball, "ball_surface", is the slave of both contact pairs of
// examples/ball_between_plates.xml (against "lower_contact" and "upper_contact"); the search
// radius keeps each node in one pair. Mesh sizes: hMin within rZone of either pole, then
// growing linearly with the distance up to hMax (Mesh.MeshSizeFactor scales them).
SetFactory("OpenCASCADE");
R = 0.01;      // ball radius, m
B = 0.012;     // plate width of the quarter model
T = 0.005;     // plate thickness
hMin = 0.0002;
rZone = 0.001;
grow = 0.4;
hMax = 0.003;
Sphere(1) = {0, 0, 0, R};
Box(2) = {0, 0, -R, R, R, 2 * R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {0, 0, -R - T, B, B, T};
Box(5) = {0, 0, R, B, B, T};
eps = 1e-5;
ballX[] = Surface In BoundingBox{-eps, -eps, -R - eps, eps, R + eps, R + eps};
ballY[] = Surface In BoundingBox{-eps, -eps, -R - eps, R + eps, eps, R + eps};
ballAll[] = Boundary{ Volume{3}; };
ballSurface[] = ballAll[];
ballSurface[] -= {ballX[], ballY[]};
lowerTop[] = Surface In BoundingBox{-eps, -eps, -R - eps, B + eps, B + eps, -R + eps};
lowerBottom[] = Surface In BoundingBox{-eps, -eps, -R - T - eps, B + eps, B + eps, -R - T + eps};
lowerX[] = Surface In BoundingBox{-eps, -eps, -R - T - eps, eps, B + eps, -R + eps};
lowerY[] = Surface In BoundingBox{-eps, -eps, -R - T - eps, B + eps, eps, -R + eps};
upperBottom[] = Surface In BoundingBox{-eps, -eps, R - eps, B + eps, B + eps, R + eps};
upperTop[] = Surface In BoundingBox{-eps, -eps, R + T - eps, B + eps, B + eps, R + T + eps};
upperX[] = Surface In BoundingBox{-eps, -eps, R - eps, eps, B + eps, R + T + eps};
upperY[] = Surface In BoundingBox{-eps, -eps, R - eps, B + eps, eps, R + T + eps};
Physical Volume("ball") = {3};
Physical Volume("lower_plate") = {4};
Physical Volume("upper_plate") = {5};
Physical Surface("ball_surface") = {ballSurface[]};
Physical Surface("lower_contact") = {lowerTop[]};
Physical Surface("lower_bottom") = {lowerBottom[]};
Physical Surface("upper_contact") = {upperBottom[]};
Physical Surface("upper_top") = {upperTop[]};
Physical Surface("symmetry_x") = {ballX[], lowerX[], upperX[]};
Physical Surface("symmetry_y") = {ballY[], lowerY[], upperY[]};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g * Max(0, Min(Sqrt(x * x + y * y + (z - %g) * (z - %g)), Sqrt(x * x + y * y + (z + %g) * (z + %g))) - %g))",
                     hMax, hMin, grow, R, R, R, R, rZone);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
