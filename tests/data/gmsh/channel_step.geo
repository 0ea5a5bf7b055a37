// hotmesh test fixture (tests/app/channel_step.hpp): a 2D channel, 25 x 10 mm, with a
// forward-facing step on its lower wall: the floor y = 0 up to the step's sharp foot at x = 10,
// the step's face up to y = 3, a fillet of radius 2 about (12, 3) on the shoulder (tangent to
// the face and to the top), and the step's top y = 5 to the outlet. Drawn with gmsh's
// OpenCASCADE kernel, as a user draws it: `gmsh -0 ... -o channel.step` writes the CAD (one
// planar face, its 7 edges in the plane z = 0), `gmsh -2 ... -format msh41` meshes it with
// quads and a few triangles, a mesh node on each CAD vertex (patches: bottom, outlet, top,
// inlet). `-setnumber lift 0.5` moves the fillet's end points and arc 0.5 out of the plane z = 0
// (for the CAD only: its edges are then no longer in the mesh's plane).
SetFactory("OpenCASCADE");
DefineConstant[lift = 0];
lc = 0.6;
Point(1) = {0, 0, 0, lc};
Point(2) = {10, 0, 0, lc};
Point(3) = {10, 3, lift, lc};
Point(4) = {12, 3, lift, lc};  // the fillet's centre
Point(5) = {12, 5, lift, lc};
Point(6) = {25, 5, 0, lc};
Point(7) = {25, 10, 0, lc};
Point(8) = {0, 10, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Circle(3) = {3, 4, 5};
Line(4) = {5, 6};
Line(5) = {6, 7};
Line(6) = {7, 8};
Line(7) = {8, 1};
Recursive Delete { Point{4}; }
If (lift == 0)
  Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
  Plane Surface(1) = {1};
  Physical Curve("bottom", 1) = {1, 2, 3, 4};
  Physical Curve("outlet", 2) = {5};
  Physical Curve("top", 3) = {6};
  Physical Curve("inlet", 4) = {7};
  Physical Surface("fluid", 10) = {1};
EndIf
Mesh.Algorithm = 6;  // 8 (Frontal-Delaunay for quads) crashes gmsh 4.8
Mesh.RecombineAll = 1;
Mesh.MeshSizeFromCurvature = 24;
