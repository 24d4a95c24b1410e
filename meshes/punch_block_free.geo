// The block of punch_block.geo (x in [-0.15,0.15], y in [-0.07,0.07], z in [-0.05,0], the same groups), unstructured:
// linear tetrahedra of size lc_min in the box x in [-xs,xs], |y| <= ys, z >= -zs under the punch's path, growing to
// lc within lc_grow of it (gmsh Box field). Its vertices lie anywhere along the path, so the punch's leading face
// ends some steps just past a vertex standing above its bottom, which it then pushes ahead (docs/scenes.md,
// "Flat punch"; scripts/flat_punch.py --mesh meshes/punch_block_free.msh). Units: metres.
//   gmsh -3 -setnumber lc_min 0.008 punch_block_free.geo -o punch_block_free.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.03, Name "Parameters/lc"]; EndIf
If (!Exists(lc_min)) lc_min = DefineNumber[0.008, Name "Parameters/lc_min"]; EndIf
If (!Exists(xs)) xs = DefineNumber[0.12, Name "Parameters/xs"]; EndIf
If (!Exists(ys)) ys = DefineNumber[0.04, Name "Parameters/ys"]; EndIf
If (!Exists(zs)) zs = DefineNumber[0.01, Name "Parameters/zs"]; EndIf
If (!Exists(lc_grow)) lc_grow = DefineNumber[0.04, Name "Parameters/lc_grow"]; EndIf
L = 0.15; W = 0.07; H = 0.05;

Box(1) = {-L, -W, -H, 2 * L, 2 * W, H};
Field[1] = Box;
Field[1].VIn = lc_min;
Field[1].VOut = lc;
Field[1].XMin = -xs; Field[1].XMax = xs;
Field[1].YMin = -ys; Field[1].YMax = ys;
Field[1].ZMin = -zs; Field[1].ZMax = 1;
Field[1].Thickness = lc_grow;
Background Field = 1;

Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;

e = 1e-6;
Physical Volume("body", 1) = {1};
Physical Surface("xmin", 1) = Surface In BoundingBox{-L-e, -W-e, -H-e, -L+e,  W+e,  e};
Physical Surface("xmax", 2) = Surface In BoundingBox{ L-e, -W-e, -H-e,  L+e,  W+e,  e};
Physical Surface("ymin", 3) = Surface In BoundingBox{-L-e, -W-e, -H-e,  L+e, -W+e,  e};
Physical Surface("ymax", 4) = Surface In BoundingBox{-L-e,  W-e, -H-e,  L+e,  W+e,  e};
Physical Surface("bottom", 5) = Surface In BoundingBox{-L-e, -W-e, -H-e, L+e, W+e, -H+e};
Physical Surface("top", 6)    = Surface In BoundingBox{-L-e, -W-e,   -e, L+e, W+e,   e};
