// hotmesh test fixture (tests/app/test_deform_cad_2d.cpp): an axisymmetric hub about the x axis,
// a cylinder of radius 1 from x = 0 to 4 then a cone down to radius 0.5 at x = 7, in a casing
// of radius 2. `-setnumber part 3 ... -o hub.step` writes the hub's solid as CAD (gmsh's
// OpenCASCADE kernel: a cylinder and a cone face, the discs at its ends); by default the 2D
// mesh of the fluid in the meridional half plane, x along the axis and y the radius (as an
// OpenFOAM wedge case is flattened): `gmsh -2 ... -format msh41` meshes it with quads, a node on
// each corner (patches: hub, casing, inlet, outlet).
SetFactory("OpenCASCADE");
DefineConstant[part = 2];
If (part == 3)
  Cylinder(1) = {0, 0, 0, 4, 0, 0, 1};
  Cone(2) = {4, 0, 0, 3, 0, 0, 1, 0.5};
  BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Else
  lc = 0.15;
  Point(1) = {0, 1, 0, lc};
  Point(2) = {4, 1, 0, lc};
  Point(3) = {7, 0.5, 0, lc};
  Point(4) = {7, 2, 0, lc};
  Point(5) = {0, 2, 0, lc};
  Line(1) = {1, 2};
  Line(2) = {2, 3};
  Line(3) = {3, 4};
  Line(4) = {4, 5};
  Line(5) = {5, 1};
  Curve Loop(1) = {1, 2, 3, 4, 5};
  Plane Surface(1) = {1};
  Physical Curve("hub", 1) = {1, 2};
  Physical Curve("outlet", 2) = {3};
  Physical Curve("casing", 3) = {4};
  Physical Curve("inlet", 4) = {5};
  Physical Surface("fluid", 10) = {1};
  Mesh.Algorithm = 6;
  Mesh.RecombineAll = 1;
EndIf
