// Two bodies for the Hertz problem: the lower half of a disc of radius 1 centred at (0, 1)
// resting on the block (-2,2)x(-1,0); they touch at (0, 0) only. The block's top is one straight
// curve with no geometric point at (0, 0), so the two meshes share no node.
R = 1.0;
lcCyl = 0.2;
lcBlock = 0.4;

// cylinder (half disc)
Point(1) = {0, R, 0, lcCyl};     // centre
Point(2) = {-R, R, 0, lcCyl};
Point(3) = {0, 0, 0, lcCyl / 2};  // the contact point
Point(4) = {R, R, 0, lcCyl};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// block
Point(11) = {-2, -1, 0, lcBlock};
Point(12) = {2, -1, 0, lcBlock};
Point(13) = {2, 0, 0, lcBlock};
Point(14) = {-2, 0, 0, lcBlock};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

Physical Surface("cylinder") = {1};
Physical Surface("block") = {2};
Physical Curve("cylinder_contact") = {1, 2};
Physical Curve("load") = {3};
Physical Curve("block_contact") = {13};
Physical Curve("fixed") = {11};
Physical Curve("block_sides") = {12, 14};
