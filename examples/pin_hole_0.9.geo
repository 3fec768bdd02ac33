// Pin of radius 0.9 in the hole of radius 1: see pin_hole.geo.
Rp = 0.9;
Include "pin_hole.geo";
