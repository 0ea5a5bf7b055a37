// hotmesh test fixture (tests/io/test_gmsh.cpp): a 1 x 0.5 x 0.25 box of nx x ny x nz = 6 x 3 x 2
// hexahedra, a transfinite quad surface extruded in layers.
nx = 6;
ny = 3;
nz = 2;
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 0.5, 0};
Point(4) = {0, 0.5, 0};
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
out[] = Extrude {0, 0, 0.25} { Surface{1}; Layers{nz}; Recombine; };
// out[0]: top, out[1]: the volume, out[2..5]: the sides swept by lines 1..4.
Physical Surface("bottom", 1) = {1};
Physical Surface("top", 2) = {out[0]};
Physical Surface("xmin", 3) = {out[5]};
Physical Surface("xmax", 4) = {out[3]};
Physical Surface("sides", 5) = {out[2], out[4]};
Physical Volume("solid", 20) = {out[1]};
