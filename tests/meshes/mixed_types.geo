// One body made of two squares, only the second recombined: a mixed triangle/quad body, which
// the loader must reject.
Point(1) = {0, 0, 0, 0.5};
Point(2) = {1, 0, 0, 0.5};
Point(3) = {2, 0, 0, 0.5};
Point(4) = {2, 1, 0, 0.5};
Point(5) = {1, 1, 0, 0.5};
Point(6) = {0, 1, 0, 0.5};
Line(1) = {1, 2};
Line(2) = {2, 5};
Line(3) = {5, 6};
Line(4) = {6, 1};
Line(5) = {2, 3};
Line(6) = {3, 4};
Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7} = 3;
Transfinite Surface{1, 2};
Recombine Surface{2};
Physical Surface("mixed") = {1, 2};
Physical Curve("bottom") = {1, 5};
