// Hertz's point contact, quarter model, all hexahedra (Hex8): the lower half of an elastic sphere
// (radius R = 1 m, centre (0, 0, R)) on an elastic block (0, B) x (0, B) x (-H, 0); they touch at
// the origin. Symmetry planes x = 0 and y = 0; the sphere's flat cut z = R carries the load, the
// block's bottom z = -H is fixed.
//
// Why structured hexahedra (docs/hertz_sphere.md has the measurements): the contact multipliers
// are nodal forces, and the pressure is a node's force over its share of the surface. On
// unstructured tetrahedra, and on structured ones (whose diagonals are mirrored by the symmetry
// planes), a node's force follows the local stiffness of the irregular elements around it while
// its area share does not, so nodal pressures scatter by +-20 % (10-17 % at the contact point of
// a structured Tet4 mesh); on a regular hexahedral grid, mirror-symmetric like the problem, they
// follow Hertz's profile to a fraction of a percent.
//
// Each body is four transfinite blocks: a zone block [0, s]^2 under (above) the contact point,
// of n x n x m equal elements (h = s / n), and three blocks around it (beyond x = s, beyond
// y = s, and beyond the zone's depth t) whose k layers grow geometrically from h outwards. In
// the sphere the zone block's bottom is the sphere patch over [0, s]^2 and the outer blocks reach
// the sphere's surface up to its equator and the top plane z = R, which they meet in the square
// [0, rho]^2 and the rest of the quarter disc. Slave (sphere) and master (block) nodes of the
// zone lie on the same x-y grid. Variants set n, m, k, s, t before including this file
// (tests/meshes/hertz_sphere_coarse.geo); Mesh.MeshSizeFactor does not apply (transfinite).
// For F = 5e5 N, E = 2e11 Pa, nu = 0.3 Hertz's contact radius is a = 15.05 mm.
R = 1.0;
B = 1.0;
H = 1.0;
If (!Exists(n))
  n = 12;       // divisions of the zone across x and y
EndIf
If (!Exists(m))
  m = 5;        // divisions through its depth
EndIf
If (!Exists(k))
  k = 10;       // layers of the blocks around it
EndIf
If (!Exists(s))
  s = 0.0225;   // the zone: x, y in [0, s] (1.5 a)
EndIf
If (!Exists(t))
  t = 0.009375; // its depth below the contact point (block) and above it (sphere)
EndIf
rho = 0.5 * R;
h = s / n;

// The ratio of a geometric progression of k divisions over the length L whose first one is h.
Macro Ratio
  lo = 1.0;
  hi = 3.0;
  For it In {1:60}
    mid = 0.5 * (lo + hi);
    If (h * (mid^k - 1) / (mid - 1) > L)
      hi = mid;
    Else
      lo = mid;
    EndIf
  EndFor
  ratio = 0.5 * (lo + hi);
Return

// ---- the sphere (centre (0, 0, R))
Point(1) = {0, 0, R};                      // centre O'
Point(2) = {0, 0, 0};                      // P, the contact point
Point(3) = {s, 0, R - Sqrt(R * R - s * s)};   // a1
Point(4) = {0, s, R - Sqrt(R * R - s * s)};   // a2
Point(5) = {s, s, R - Sqrt(R * R - 2 * s * s)};   // a3
Point(6) = {0, 0, t};  Point(7) = {s, 0, t};  Point(8) = {0, s, t};  Point(9) = {s, s, t};   // b0..b3
Point(10) = {R, 0, R}; Point(11) = {0, R, R}; Point(12) = {R / Sqrt(2), R / Sqrt(2), R};  // E1 E2 Ed
Point(13) = {rho, 0, R}; Point(14) = {0, rho, R}; Point(15) = {rho, rho, R};           // d1 d2 d3
Point(16) = {s, 0, R}; Point(17) = {0, s, R};   // centres of the small circles x = s, y = s

// zone edges (n, m)
Circle(1) = {2, 1, 3};    // P-a1
Circle(2) = {2, 1, 4};    // P-a2
Circle(3) = {3, 16, 5};   // a1-a3 (x = s)
Circle(4) = {4, 17, 5};   // a2-a3 (y = s)
Line(5) = {6, 7};  Line(6) = {6, 8};  Line(7) = {7, 9};  Line(8) = {8, 9};   // b0-b1 b0-b2 b1-b3 b2-b3
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};   // vertical
// outer tangential edges (n) and outer depth edges (m)
Circle(13) = {10, 1, 12};  // E1-Ed
Circle(14) = {11, 1, 12};  // E2-Ed
Line(15) = {13, 15}; Line(16) = {14, 15}; Line(17) = {1, 13}; Line(18) = {1, 14};
Line(19) = {10, 13}; Line(20) = {11, 14}; Line(21) = {12, 15};   // E1-d1, E2-d2, Ed-d3 (m)
// radial edges (k), inner to outer
Circle(22) = {3, 1, 10};  // a1-E1
Circle(23) = {4, 1, 11};  // a2-E2
Circle(24) = {5, 1, 12};  // a3-Ed
Line(25) = {7, 13}; Line(26) = {8, 14}; Line(27) = {9, 15}; Line(28) = {6, 1};

// faces
Curve Loop(1) = {1, 3, -4, -2};  Surface(1) = {1} In Sphere {1};      // cap bottom
Curve Loop(2) = {5, 7, -8, -6};  Plane Surface(2) = {2};              // cap top z = t
Curve Loop(3) = {2, 11, -6, -9}; Plane Surface(3) = {3};              // cap x = 0
Curve Loop(4) = {1, 10, -5, -9}; Plane Surface(4) = {4};              // cap y = 0
Curve Loop(5) = {3, 12, -7, -10}; Plane Surface(5) = {5};             // x = s
Curve Loop(6) = {4, 12, -8, -11}; Plane Surface(6) = {6};             // y = s
Curve Loop(7) = {22, 13, -24, -3}; Surface(7) = {7} In Sphere {1};    // X bottom
Curve Loop(8) = {23, 14, -24, -4}; Surface(8) = {8} In Sphere {1};    // Y bottom
Curve Loop(9) = {19, 15, -21, -13}; Plane Surface(9) = {9};           // X outer z = R
Curve Loop(10) = {20, 16, -21, -14}; Plane Surface(10) = {10};        // Y outer z = R
Curve Loop(11) = {17, 15, -16, -18}; Plane Surface(11) = {11};        // Z outer z = R
Curve Loop(12) = {22, 19, -25, -10}; Plane Surface(12) = {12};        // X y = 0
Curve Loop(13) = {23, 20, -26, -11}; Plane Surface(13) = {13};        // Y x = 0
Curve Loop(14) = {24, 21, -27, -12}; Plane Surface(14) = {14};        // X|Y diagonal
Curve Loop(15) = {7, 27, -15, -25}; Plane Surface(15) = {15};         // X|Z
Curve Loop(16) = {8, 27, -16, -26}; Plane Surface(16) = {16};         // Y|Z
Curve Loop(17) = {5, 25, -17, -28}; Plane Surface(17) = {17};         // Z y = 0
Curve Loop(18) = {6, 26, -18, -28}; Plane Surface(18) = {18};         // Z x = 0
Surface Loop(1) = {1, 2, 3, 4, 5, 6};        Volume(1) = {1};   // cap
Surface Loop(2) = {5, 7, 9, 12, 14, 15};     Volume(2) = {2};   // X
Surface Loop(3) = {6, 8, 10, 13, 14, 16};    Volume(3) = {3};   // Y
Surface Loop(4) = {2, 11, 15, 16, 17, 18};   Volume(4) = {4};   // Z

Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8, 13, 14, 15, 16, 17, 18} = n + 1;
Transfinite Curve{9, 10, 11, 12, 19, 20, 21} = m + 1;
radial[] = {22, 23, 24, 25, 26, 27, 28};
lens[] = {Pi / 2 * R - Asin(s / R), Pi / 2 * R - Asin(s / R), Pi / 2 * R - Asin(Sqrt(2) * s / R),
          Sqrt((rho - s)^2 + (R - t)^2), Sqrt((rho - s)^2 + (R - t)^2),
          Sqrt(2 * (rho - s)^2 + (R - t)^2), R - t};
For i In {0:#radial[] - 1}
  L = lens[i]; Call Ratio;
  Transfinite Curve{radial[i]} = k + 1 Using Progression ratio;
EndFor
Transfinite Surface{1:18};
Recombine Surface{1:18};
Transfinite Volume{1:4};
Recombine Volume{1:4};

// ---- block (0, B) x (0, B) x (-H, 0): the zone box [0, s]^2 x [-t, 0] and three blocks
Point(101) = {0, 0, 0}; Point(102) = {s, 0, 0}; Point(103) = {0, s, 0}; Point(104) = {s, s, 0};
Point(105) = {0, 0, -t}; Point(106) = {s, 0, -t}; Point(107) = {0, s, -t}; Point(108) = {s, s, -t};
Point(109) = {B, 0, 0}; Point(110) = {0, B, 0}; Point(111) = {B, B, 0};
Point(112) = {0, 0, -H}; Point(113) = {B, 0, -H}; Point(114) = {0, B, -H}; Point(115) = {B, B, -H};
Line(101) = {101, 102}; Line(102) = {101, 103}; Line(103) = {102, 104}; Line(104) = {103, 104};
Line(105) = {105, 106}; Line(106) = {105, 107}; Line(107) = {106, 108}; Line(108) = {107, 108};
Line(109) = {101, 105}; Line(110) = {102, 106}; Line(111) = {103, 107}; Line(112) = {104, 108};
Line(113) = {109, 111}; Line(114) = {110, 111}; Line(115) = {113, 115}; Line(116) = {114, 115};
Line(117) = {112, 113}; Line(118) = {112, 114};
Line(119) = {109, 113}; Line(120) = {110, 114}; Line(121) = {111, 115};
Line(122) = {102, 109}; Line(123) = {103, 110}; Line(124) = {104, 111};
Line(125) = {106, 113}; Line(126) = {107, 114}; Line(127) = {108, 115}; Line(128) = {105, 112};
Curve Loop(101) = {101, 103, -104, -102}; Plane Surface(101) = {101};   // zone top z = 0
Curve Loop(102) = {105, 107, -108, -106}; Plane Surface(102) = {102};   // zone bottom
Curve Loop(103) = {102, 111, -106, -109}; Plane Surface(103) = {103};   // x = 0
Curve Loop(104) = {101, 110, -105, -109}; Plane Surface(104) = {104};   // y = 0
Curve Loop(105) = {103, 112, -107, -110}; Plane Surface(105) = {105};   // x = s
Curve Loop(106) = {104, 112, -108, -111}; Plane Surface(106) = {106};   // y = s
Curve Loop(107) = {122, 113, -124, -103}; Plane Surface(107) = {107};   // X top z = 0
Curve Loop(108) = {123, 114, -124, -104}; Plane Surface(108) = {108};   // Y top z = 0
Curve Loop(109) = {119, 115, -121, -113}; Plane Surface(109) = {109};   // X outer x = B
Curve Loop(110) = {120, 116, -121, -114}; Plane Surface(110) = {110};   // Y outer y = B
Curve Loop(111) = {117, 115, -116, -118}; Plane Surface(111) = {111};   // Z outer z = -H
Curve Loop(112) = {122, 119, -125, -110}; Plane Surface(112) = {112};   // X y = 0
Curve Loop(113) = {123, 120, -126, -111}; Plane Surface(113) = {113};   // Y x = 0
Curve Loop(114) = {124, 121, -127, -112}; Plane Surface(114) = {114};   // X|Y
Curve Loop(115) = {107, 127, -115, -125}; Plane Surface(115) = {115};   // X|Z
Curve Loop(116) = {108, 127, -116, -126}; Plane Surface(116) = {116};   // Y|Z
Curve Loop(117) = {105, 125, -117, -128}; Plane Surface(117) = {117};   // Z y = 0
Curve Loop(118) = {106, 126, -118, -128}; Plane Surface(118) = {118};   // Z x = 0
Surface Loop(101) = {101, 102, 103, 104, 105, 106};   Volume(101) = {101};
Surface Loop(102) = {105, 107, 109, 112, 114, 115};   Volume(102) = {102};
Surface Loop(103) = {106, 108, 110, 113, 114, 116};   Volume(103) = {103};
Surface Loop(104) = {102, 111, 115, 116, 117, 118};   Volume(104) = {104};
Transfinite Curve{101:108, 113:118} = n + 1;
Transfinite Curve{109:112, 119:121} = m + 1;
bradial[] = {122, 123, 124, 125, 126, 127, 128};
blens[] = {B - s, B - s, Sqrt(2) * (B - s), Sqrt((B - s)^2 + (H - t)^2),
           Sqrt((B - s)^2 + (H - t)^2), Sqrt(2 * (B - s)^2 + (H - t)^2), H - t};
For i In {0:#bradial[] - 1}
  L = blens[i]; Call Ratio;
  Transfinite Curve{bradial[i]} = k + 1 Using Progression ratio;
EndFor
Transfinite Surface{101:118};
Recombine Surface{101:118};
Transfinite Volume{101:104};
Recombine Volume{101:104};

Physical Volume("sphere") = {1:4};
Physical Volume("block") = {101:104};
Physical Surface("sphere_contact") = {1, 7, 8};
Physical Surface("sphere_top") = {9, 10, 11};
Physical Surface("block_contact") = {101, 107, 108};
Physical Surface("block_bottom") = {111};
Physical Surface("symmetry_x") = {3, 13, 18, 103, 113, 118};
Physical Surface("symmetry_y") = {4, 12, 17, 104, 112, 117};
