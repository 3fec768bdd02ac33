// Two blocks stacked on y = 0.5 with non-matching meshes (the contact patch test): the lower
// block (0, 1) x (0, 0.5) with 5 divisions along x, the upper (0, 1) x (0.5, 1) with 7, each
// body with its own nodes on the interface.
SetFactory("Built-in");
nl = 5; nu = 7;
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 0.5, 0}; Point(4) = {0, 0.5, 0};
Point(5) = {0, 0.5, 0}; Point(6) = {1, 0.5, 0}; Point(7) = {1, 1, 0}; Point(8) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Transfinite Line{1, 3} = nl + 1; Transfinite Line{2, 4} = 4;
Transfinite Line{5, 7} = nu + 1; Transfinite Line{6, 8} = 5;
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Surface{1, 2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("lower_bottom") = {1};
Physical Curve("lower_left") = {4};
Physical Curve("lower_top") = {3};
Physical Curve("upper_bottom") = {5};
Physical Curve("upper_left") = {8};
Physical Curve("upper_top") = {7};
