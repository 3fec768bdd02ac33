// The unit cube of docs/hertz_sphere.md ("Dual iterations against the number of subdomains"):
// N x N x N uniform Hex8 (Gmsh transfinite), bottom z = 0 ("bottom"), top z = 1 ("top"). With the
// top tied to a rigid plane its METIS subdomains cut the tied surface, which is what issue 13's
// scaling groups are about (tests/CMakeLists.txt, "tied_cube").
N = 14; r = 1.0;
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};
Curve Loop(1) = {1, 2, -3, -4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = N + 1 Using Progression r;
Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{N}; Recombine; };
Physical Volume("box") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
