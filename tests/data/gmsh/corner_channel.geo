// hotmesh test fixture (tests/app/test_deform_corners_on_nodes.cpp): a 2D channel 14 mm long and
// 5 mm high drawn as CAD, whose lower wall has corners of every kind, each a CAD vertex and so a
// mesh node (gmsh puts a node on every vertex, as every mesher working from CAD does):
//   (4, 0)    concave, 90 degrees: the foot of a forward-facing step
//   (4, 1)    convex, 90 degrees: its shoulder
//   (6, 1)    concave, 63.4 degrees: the foot of a ridge
//   (6.5, 2)  convex, 126.9 degrees: the ridge's tip, sharper than a right angle
//   (7, 1)    concave, 63.4 degrees: its other foot
//   (9, 1)    convex, 90 degrees: the shoulder of a backward-facing step
//   (9, 0)    concave, 90 degrees: its foot
// split = 0: the lower wall is one patch, `floor`; split = 1: one patch per straight piece,
// floor_1 ... floor_8, split at the corners. triangles = 1: triangles instead of quads.
// `gmsh -2 -format msh41 corner_channel.geo -o channel.msh`.
SetFactory("OpenCASCADE");
DefineConstant[split = 0, triangles = 0];
floor[] = {0, 0, 4, 0, 4, 1, 6, 1, 6.5, 2, 7, 1, 9, 1, 9, 0, 14, 0};  // x, y of each vertex
n = #floor[] / 2;
For i In {0 : n - 1}
  Point(i + 1) = {floor[2 * i], floor[2 * i + 1], 0};
EndFor
Point(n + 1) = {14, 5, 0};
Point(n + 2) = {0, 5, 0};
For i In {1 : n - 1}
  Line(i) = {i, i + 1};
EndFor
Line(n) = {n, n + 1};          // outlet
Line(n + 1) = {n + 1, n + 2};  // top
Line(n + 2) = {n + 2, 1};      // inlet
Curve Loop(1) = {1 : n + 2};
Plane Surface(1) = {1};
If (split)
  For i In {1 : n - 1}
    Physical Curve(Sprintf("floor_%g", i)) = {i};
  EndFor
Else
  Physical Curve("floor") = {1 : n - 1};
EndIf
Physical Curve("outlet") = {n};
Physical Curve("top") = {n + 1};
Physical Curve("inlet") = {n + 2};
Physical Surface("fluid") = {1};
Mesh.CharacteristicLengthMax = 0.5;
Mesh.CharacteristicLengthFromPoints = 0;
Field[1] = Distance;
Field[1].CurvesList = {1 : n - 1};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.15;
Field[2].SizeMax = 0.5;
Field[2].DistMin = 0.2;
Field[2].DistMax = 2;
Background Field = 2;
Mesh.Algorithm = 6;
Mesh.RecombineAll = (triangles == 0);
