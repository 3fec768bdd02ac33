// The unit cube in tetrahedra (OpenCASCADE box: surfaces 1..6 are x = 0, x = 1, y = 0, y = 1,
// z = 0, z = 1). A 3D mesh for the Gmsh reader's tests.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMin = 0.5;
Mesh.MeshSizeMax = 0.5;
Physical Volume("cube") = {1};
Physical Surface("xmin") = {1};
Physical Surface("xmax") = {2};
Physical Surface("ymin") = {3};
Physical Surface("ymax") = {4};
Physical Surface("bottom") = {5};
Physical Surface("top") = {6};
