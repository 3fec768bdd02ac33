// A quarter of the lower half of a sphere (radius 1, centre (0, 0, 1)) resting on a block
// (0,2)x(0,2)x(-1,0): they touch at the origin only. Symmetry planes x = 0 and y = 0. A 3D
// two-body contact mesh for the Gmsh reader's and the node-to-face search's tests.
SetFactory("OpenCASCADE");
R = 1.0;
Sphere(1) = {0, 0, R, R};
Box(2) = {0, 0, 0, R, R, R};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {0, 0, -1, 2, 2, 1};
Mesh.MeshSizeMax = 0.4;
MeshSize{ PointsOf{ Volume{4}; } } = 0.5;
MeshSize{ Point{:} } = 0.4;
eps = 1e-6;
sphereTop[] = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
sphereX[] = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
sphereY[] = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps};
sphereAll[] = Boundary{ Volume{3}; };
blockTop[] = Surface In BoundingBox{-eps, -eps, -eps, 2 + eps, 2 + eps, eps};
blockBottom[] = Surface In BoundingBox{-eps, -eps, -1 - eps, 2 + eps, 2 + eps, -1 + eps};
blockX[] = Surface In BoundingBox{-eps, -eps, -1 - eps, eps, 2 + eps, eps};
blockY[] = Surface In BoundingBox{-eps, -eps, -1 - eps, 2 + eps, eps, eps};
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
