// Cylinder radius 0.5, height 1, axis z, centred at the origin (z in [-0.5,0.5]).
// Unstructured linear tetrahedra. Units: metres.
//   gmsh -3 -setnumber lc 0.07 cylinder.geo -o cylinder.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.07, Name "Parameters/lc"]; EndIf

Cylinder(1) = {0, 0, -0.5, 0, 0, 1, 0.5};
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;

e = 1e-6;
Physical Volume("body", 1) = {1};
sb() = Surface In BoundingBox{-0.5-e, -0.5-e, -0.5-e, 0.5+e, 0.5+e, -0.5+e};
st() = Surface In BoundingBox{-0.5-e, -0.5-e,  0.5-e, 0.5+e, 0.5+e,  0.5+e};
ss() = Abs(Boundary{Volume{1};});
ss() -= sb();
ss() -= st();
Physical Surface("side", 1)   = {ss()};
Physical Surface("bottom", 2) = {sb()};
Physical Surface("top", 3)    = {st()};
