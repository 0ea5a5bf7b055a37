// hotmesh test fixture (tests/app/test_deform_corners_on_nodes.cpp): a duct 12 mm long, 4 mm high
// and 3 mm wide drawn as CAD, whose floor has a forward-facing step 1 mm high at x = 5: a concave
// edge at its foot (5, 0) and a convex one at its shoulder (5, 1), both at 90 degrees and both
// CAD edges, so the mesh has a row of nodes along each (as every mesher working from CAD does).
// The floor is three plane faces; the duct's sides z = 0 and z = 3 are `front` and `back`.
// tets = 0: the side's quads extruded into 8 layers of hexahedra; tets = 1: tetrahedra.
// `gmsh -3 -format msh41 step_duct.geo -o duct.msh`; `gmsh -0 step_duct.geo -o duct.step`.
SetFactory("OpenCASCADE");
DefineConstant[tets = 0];
Point(1) = {0, 0, 0};
Point(2) = {5, 0, 0};
Point(3) = {5, 1, 0};
Point(4) = {12, 1, 0};
Point(5) = {12, 4, 0};
Point(6) = {0, 4, 0};
For i In {1 : 5}
  Line(i) = {i, i + 1};
EndFor
Line(6) = {6, 1};
Curve Loop(1) = {1 : 6};
Plane Surface(1) = {1};
Mesh.CharacteristicLengthMax = 0.4;
If (tets)
  out[] = Extrude {0, 0, 3} { Surface{1}; };
Else
  Mesh.RecombineAll = 1;
  Mesh.Algorithm = 6;
  out[] = Extrude {0, 0, 3} { Surface{1}; Layers{8}; Recombine; };
EndIf
// out[0]: the back side, out[1]: the volume, out[2 .. 7]: the faces swept from lines 1 .. 6.
Physical Surface("floor") = {out[2], out[3], out[4]};
Physical Surface("outlet") = {out[5]};
Physical Surface("top") = {out[6]};
Physical Surface("inlet") = {out[7]};
Physical Surface("front") = {1};
Physical Surface("back") = {out[0]};
Physical Volume("fluid") = {out[1]};
