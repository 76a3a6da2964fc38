// The unit square (0, 1)² as a structured mesh of n × n squares, each cut along the rising
// diagonal (x_i, y_j)–(x_{i+1}, y_{j+1}): the triangles of contactlab's own rectangle mesh
// (diagonal = "up"), in Gmsh's node and element order. Physical groups: the four sides and the
// body. Generated with `python3 examples/meshes/generate.py` (all three formats).
If (!Exists(n))
  n = 8;
EndIf
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Right;
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("body") = {1};
