// The CI variant of examples/hertz_sphere_elastic.geo: a zone of 10 x 10 x 4 hexahedra of h = 2 mm
// (a / 7.5) over [0, 20 mm]^2 (1.33 a), 10 layers around it (docs/hertz_sphere.md).
n = 10;
m = 4;
k = 10;
s = 0.02;
t = 0.008;
Include "../../examples/hertz_sphere_elastic.geo";
