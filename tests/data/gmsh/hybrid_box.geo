// hotmesh test fixture (tests/io/test_cgns_hybrid.cpp, test_foam_hybrid.cpp): every 3D cell
// type in one conforming mesh. The box [0,2] x [0,1] x [0,1.3]: on x < 1, z < 1 structured
// hexahedra; on x > 1, z < 1 tetrahedra, with pyramids where they meet the hexahedra's quads
// at x = 1; above z = 1 two extruded layers, hexahedra over the quads and prisms over the
// triangles. Boundary patches of triangles and quads: bottom, top, xmin, xmax, sides.
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
Transfinite Surface{1};
Recombine Surface{1};
hex[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
tet[] = Extrude {0, 0, 1} { Surface{2}; };
Transfinite Curve{:} = 3;
Extrude {0, 0, 0.3} { Surface{hex[0], tet[0]}; Layers{2}; Recombine; }
e = 1e-6;
Physical Surface("bottom", 1) = Surface In BoundingBox {-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top", 2) = Surface In BoundingBox {-e, -e, 1.3 - e, 2 + e, 1 + e, 1.3 + e};
Physical Surface("xmin", 3) = Surface In BoundingBox {-e, -e, -e, e, 1 + e, 1.3 + e};
Physical Surface("xmax", 4) = Surface In BoundingBox {2 - e, -e, -e, 2 + e, 1 + e, 1.3 + e};
Physical Surface("sides", 5) = Surface In BoundingBox {-e, -e, -e, 2 + e, e, 1.3 + e};
Physical Surface("sides", 5) += Surface In BoundingBox {-e, 1 - e, -e, 2 + e, 1 + e, 1.3 + e};
Physical Volume("fluid", 10) = Volume{:};
