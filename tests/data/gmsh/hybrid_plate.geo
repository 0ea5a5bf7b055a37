// hotmesh test fixture (tests/io/test_cgns_hybrid.cpp): a 2D mesh of quads and triangles. The
// plate [0,2] x [0,1]: structured quads on x < 1, triangles on x > 1. Patches of lines:
// bottom (y = 0), top (y = 1), left (x = 0), right (x = 2).
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {2, 0, 0};
Point(4) = {2, 1, 0};
Point(5) = {1, 1, 0};
Point(6) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 5};
Line(3) = {5, 6};
Line(4) = {6, 1};
Line(5) = {2, 3};
Line(6) = {3, 4};
Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Transfinite Curve{1:7} = 4;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("bottom", 1) = {1, 5};
Physical Curve("top", 2) = {3, 7};
Physical Curve("left", 3) = {4};
Physical Curve("right", 4) = {6};
Physical Surface("fluid", 10) = {1, 2};
