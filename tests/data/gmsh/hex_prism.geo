// hotmesh test fixture (tests/io/test_gmsh.cpp): mixed hexahedra and prisms. A 2 x 1 plate whose
// left unit square has 2 x 2 quads and whose right one 2 x 2 x 2 triangles, extruded by 0.5 in
// 3 layers: 12 hexahedra and 24 prisms, quads and triangles on the boundary.
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
Transfinite Curve{1:7} = 3;
Transfinite Surface{1, 2};
Recombine Surface{1};
out[] = Extrude {0, 0, 0.5} { Surface{1, 2}; Layers{3}; Recombine; };
e = 1e-6;
Physical Surface("bottom", 1) = Surface In BoundingBox {-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top", 2) = Surface In BoundingBox {-e, -e, 0.5 - e, 2 + e, 1 + e, 0.5 + e};
Physical Surface("xmin", 3) = Surface In BoundingBox {-e, -e, -e, e, 1 + e, 0.5 + e};
Physical Surface("xmax", 4) = Surface In BoundingBox {2 - e, -e, -e, 2 + e, 1 + e, 0.5 + e};
Physical Surface("front", 5) = Surface In BoundingBox {-e, -e, -e, 2 + e, e, 0.5 + e};
Physical Surface("back", 6) = Surface In BoundingBox {-e, 1 - e, -e, 2 + e, 1 + e, 0.5 + e};
Physical Volume("hexes", 20) = {out[1]};
Physical Volume("prisms", 21) = {out[7]};
