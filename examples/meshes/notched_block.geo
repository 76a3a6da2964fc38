// A block (0, 6) × (0, 3) with a V-notch cut into its top (apex at (3, 1.8)), resting on a
// lubricated foundation. Boundary groups: "base" (y = 0, the contact part), "sides" (x = 0 and
// x = 6), "top" (the top on both sides of the notch), "notch" (the two notch flanks). Region:
// "block".
h = 0.3;
Point(1) = {0, 0, 0, h};
Point(2) = {6, 0, 0, h};
Point(3) = {6, 3, 0, h};
Point(4) = {3.6, 3, 0, h / 2};
Point(5) = {3, 1.8, 0, h / 4};
Point(6) = {2.4, 3, 0, h / 2};
Point(7) = {0, 3, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Physical Curve("base") = {1};
Physical Curve("sides") = {2, 7};
Physical Curve("top") = {3, 6};
Physical Curve("notch") = {4, 5};
Physical Surface("block") = {1};
