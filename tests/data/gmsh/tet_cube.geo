// hotmesh test fixture (tests/io/test_gmsh.cpp): the unit cube meshed with tetrahedra
// (unstructured, so the test checks volume and boundary coverage rather than counts).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.CharacteristicLengthMax = 0.35;
Physical Surface("walls", 1) = {1, 2, 3, 4, 5, 6};
Physical Volume("solid", 2) = {1};
