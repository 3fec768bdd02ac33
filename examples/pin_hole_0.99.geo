// Pin of radius 0.99 in the hole of radius 1: see pin_hole.geo.
Rp = 0.99;
Include "pin_hole.geo";
