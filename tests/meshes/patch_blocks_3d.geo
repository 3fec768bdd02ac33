// Two blocks stacked on z = 0.5 with non-matching unstructured tetrahedral meshes (the contact
// patch test in 3D): the lower block (0, 1)^2 x (0, 0.5) of size 0.3, the upper (0, 1)^2 x
// (0.5, 1) of size 0.22, each body with its own nodes on the interface (no fragments).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Box(2) = {0, 0, 0.5, 1, 1, 0.5};
MeshSize{PointsOf{Volume{1};}} = 0.3;
MeshSize{PointsOf{Volume{2};}} = 0.22;
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
// OpenCASCADE numbers a box's faces x = 0, x = 1, y = 0, y = 1, z = 0, z = 1.
Physical Surface("lower_x0") = {1};
Physical Surface("lower_y0") = {3};
Physical Surface("lower_bottom") = {5};
Physical Surface("lower_top") = {6};
Physical Surface("upper_x0") = {7};
Physical Surface("upper_y0") = {9};
Physical Surface("upper_bottom") = {11};
Physical Surface("upper_top") = {12};
