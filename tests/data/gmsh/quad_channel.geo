// hotmesh test fixture (tests/io/test_gmsh.cpp): a 2 x 1 channel meshed as nx x ny = 10 x 4 quads.
// Patches: inlet (x = 0), outlet (x = 2), walls (y = 0 and y = 1) and floor (y = 0 again, so its
// edges are in two physical groups). Cells: fluid and zone, both on the one surface, so every
// cell is in two physical groups.
nx = 10;
ny = 4;
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("inlet", 1) = {4};
Physical Curve("outlet", 2) = {2};
Physical Curve("walls", 3) = {1, 3};
Physical Curve("floor", 4) = {1};
Physical Surface("fluid", 10) = {1};
Physical Surface("zone", 11) = {1};
