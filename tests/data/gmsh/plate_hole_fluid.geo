// hotmesh test fixture (tests/app/test_deform_trimmed_faces.cpp): the fluid over a 10 x 10 x 2 mm
// plate with a round hole of radius 2 about the z axis, and the hole itself. The fluid is the box
// [-5, 5] x [-5, 5] x [2, 5] joined with the hole, so its boundary holds the plate's top face
// (the plane z = 2 trimmed by the hole's circle) and the hole's wall, sharing that circle.
//
// cone_deg = 0: the hole is a cylinder of radius 2 through the plate (the wall turns by 90
// degrees at the circle). cone_deg > 0: a countersunk hole: a cone from the circle of radius 2
// at z = 2 down to radius 1 at `cone_deg` to the plate, then a cylinder of radius 1 to z = 0; the
// wall turns by only cone_deg at the top circle.
//
// `gmsh -3 ... -format msh41` meshes it with tetrahedra (patches: wall, hole_end, ceiling,
// side_xmin, side_xmax, side_ymin, side_ymax); `gmsh -0 ... -o fluid.step` writes its CAD.
SetFactory("OpenCASCADE");
DefineConstant[cone_deg = 0];
Box(1) = {-5, -5, 2, 10, 10, 3};
If (cone_deg > 0)
  zc = 2 - Tan(cone_deg * Pi / 180);
  Cone(2) = {0, 0, zc, 0, 0, 2 - zc, 1, 2};
  Cylinder(3) = {0, 0, 0, 0, 0, zc, 1};
  v[] = BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
Else
  Cylinder(2) = {0, 0, 0, 0, 0, 2, 2};
  v[] = BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; };
EndIf
e = 1e-6;
top[] = Surface In BoundingBox {-5 - e, -5 - e, 2 - e, 5 + e, 5 + e, 2 + e};
bottom[] = Surface In BoundingBox {-2 - e, -2 - e, -e, 2 + e, 2 + e, e};
hole[] = Surface In BoundingBox {-2 - e, -2 - e, -e, 2 + e, 2 + e, 2 + e};
hole[] -= top[];
hole[] -= bottom[];
Physical Surface("wall", 1) = {top[], hole[]};
Physical Surface("hole_end", 2) = {bottom[]};
Physical Surface("ceiling", 3) = Surface In BoundingBox {-5 - e, -5 - e, 5 - e, 5 + e, 5 + e, 5 + e};
Physical Surface("side_xmin", 4) = Surface In BoundingBox {-5 - e, -5 - e, 2 - e, -5 + e, 5 + e, 5 + e};
Physical Surface("side_xmax", 5) = Surface In BoundingBox {5 - e, -5 - e, 2 - e, 5 + e, 5 + e, 5 + e};
Physical Surface("side_ymin", 6) = Surface In BoundingBox {-5 - e, -5 - e, 2 - e, 5 + e, -5 + e, 5 + e};
Physical Surface("side_ymax", 7) = Surface In BoundingBox {-5 - e, 5 - e, 2 - e, 5 + e, 5 + e, 5 + e};
Physical Volume("fluid", 10) = {v[]};
// Cells of 0.3 mm along the hole's rim, growing to 1.2 mm away from it (about 1000 nodes).
Field[1] = MathEval;
Field[1].F = "0.3 + 0.25 * Abs(Sqrt(x * x + y * y) - 2) + 0.15 * Abs(z - 2)";
Background Field = 1;
Mesh.MeshSizeMin = 0.3;
Mesh.MeshSizeMax = 1.2;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
