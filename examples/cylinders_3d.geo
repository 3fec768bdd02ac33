// The reference paper's two cylinders (examples/two_cylinders.geo, included: the same half
// model, points, curves, surfaces and mesh-size field) extruded along z into a slab of thickness
// T in `layers` layers of hexahedra. The two surfaces are recombined into quadrilaterals first
// (Blossom, as the 2D runs' "Quadrilaterals" option does), so that every layer repeats the 2D
// quadrilateral mesh: the bodies are Hex8 and the contact surfaces quadrilaterals. With
// symmetry planes (u_z = 0) on both end faces z = 0 and z = T the problem is plane strain.
Include "two_cylinders.geo";
Delete Physicals;  // the 2D groups (bodies are surfaces there); the 3D ones follow
If (!Exists(T))
  T = 0.05;
EndIf
If (!Exists(layers))
  layers = 2;
EndIf
Mesh.RecombinationAlgorithm = 1;
Recombine Surface{1, 2};
// The bodies touch along the line x = y = 0 but must share no node there (as in 2D, where they
// have separate points at the origin). An extrusion merges every pair of coincident points
// (Geometry.AutoCoherence), the contact points' copies too; so the block is extruded away from
// the cylinder, shifted by `away` along x (a power of two: the shift and its undoing are exact),
// and moved back with the merging off.
away = 16;
Translate {away, 0, 0} { Surface{2}; }
// Extrude returns the top surface, the volume, then the sides swept by the curves of the
// surface's loop in order: cylinder {1: arc, 2: top edge, 3: axis}, block {11: axis, 12:
// bottom, 13: far side, 14: top}.
cyl[] = Extrude {0, 0, T} { Surface{1}; Layers{layers}; Recombine; };
blk[] = Extrude {0, 0, T} { Surface{2}; Layers{layers}; Recombine; };
Geometry.AutoCoherence = 0;
Translate {-away, 0, 0} { Volume{blk[1]}; }
Physical Volume("cylinder") = {cyl[1]};
Physical Volume("block") = {blk[1]};
Physical Surface("cylinder_contact") = {cyl[2]};
Physical Surface("load") = {cyl[3]};
Physical Surface("cylinder_symmetry") = {cyl[4]};
Physical Surface("block_symmetry") = {blk[2]};
Physical Surface("fixed") = {blk[3]};
Physical Surface("block_contact") = {blk[5]};
Physical Surface("ends") = {1, 2, cyl[0], blk[0]};
