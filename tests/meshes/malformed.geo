// A geometry with a syntax error on line 3: loading it must fail with Gmsh's parser message.
Point(1) = {0, 0, 0, 1.0};
Line(1) = {1, ;
