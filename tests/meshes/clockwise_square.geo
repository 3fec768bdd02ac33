// A unit square whose curve loop runs clockwise: Gmsh gives the surface the normal -z and its
// elements clockwise node order, which the reader must turn counter-clockwise.
Point(1) = {0, 0, 0, 0.25};
Point(2) = {0, 1, 0, 0.25};
Point(3) = {1, 1, 0, 0.25};
Point(4) = {1, 0, 0, 0.25};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("square") = {1};
Physical Curve("boundary") = {1, 2, 3, 4};
