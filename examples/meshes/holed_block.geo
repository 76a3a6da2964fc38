// A block with slanted sides and an off-centre circular hole, resting on a lubricated foundation:
// the plane family's envelope mesh (an input not shaped for a case: curved and slanted boundaries,
// a hole, an unstructured Delaunay mesh with graded sizes towards the hole). Parameter h, the edge
// length on the outer boundary (h/2 on the hole). Boundary groups: "base" (y = 0, the contact
// part), "sides" (the two slanted sides), "top", "hole". Region: "block".
If (!Exists(h)) h = 0.3; EndIf
Point(1) = {0, 0, 0, h};
Point(2) = {6, 0, 0, h};
Point(3) = {5.2, 3, 0, h};
Point(4) = {0.7, 3, 0, h};
Point(5) = {2.6, 1.4, 0, h / 2};
Point(6) = {3.3, 1.4, 0, h / 2};
Point(7) = {2.6, 2.1, 0, h / 2};
Point(8) = {1.9, 1.4, 0, h / 2};
Point(9) = {2.6, 0.7, 0, h / 2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Circle(5) = {6, 5, 7};
Circle(6) = {7, 5, 8};
Circle(7) = {8, 5, 9};
Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Curve("base") = {1};
Physical Curve("sides") = {2, 4};
Physical Curve("top") = {3};
Physical Curve("hole") = {5, 6, 7, 8};
Physical Surface("block") = {1};
