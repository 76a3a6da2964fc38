// A strip (0, 2) × (0, 1) of two materials in series: "soft" on x < 1, "stiff" on x > 1, the
// interface x = 1 a mesh line. Boundary groups: "left" (x = 0), "bottom" (y = 0), "right" (x = 2),
// "top" (y = 1). Unstructured triangles of size about 0.25.
h = 0.25;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {2, 0, 0, h};
Point(4) = {2, 1, 0, h};
Point(5) = {1, 1, 0, h};
Point(6) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Physical Curve("bottom") = {1, 2};
Physical Curve("right") = {3};
Physical Curve("top") = {4, 5};
Physical Curve("left") = {6};
Physical Surface("soft") = {1};
Physical Surface("stiff") = {2};
