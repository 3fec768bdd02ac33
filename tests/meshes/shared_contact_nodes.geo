// Two unit squares on top of each other that share their common edge (one curve in both loops),
// so the contact pair's surfaces share every node: an error for a contact problem
// (tests/inputs/bad_shared_contact_nodes.xml).
Point(1) = {0, -1, 0, 0.25};
Point(2) = {1, -1, 0, 0.25};
Point(3) = {1, 0, 0, 0.25};
Point(4) = {0, 0, 0, 0.25};
Point(5) = {1, 1, 0, 0.25};
Point(6) = {0, 1, 0, 0.25};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("bottom") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("upper_bottom") = {3};
Physical Curve("top") = {6};
