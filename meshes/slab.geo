// Slab x,y in [-2,2], z in [-0.25,0] (top face at z = 0, the contact face).
// Unstructured linear tetrahedra. Units: metres.
//   gmsh -3 -setnumber lc 0.125 slab.geo -o slab.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.125, Name "Parameters/lc"]; EndIf
H = 0.25;

Box(1) = {-2, -2, -H, 4, 4, H};
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;

e = 1e-6;
Physical Volume("body", 1) = {1};
Physical Surface("xmin", 1) = Surface In BoundingBox{-2-e, -2-e, -H-e, -2+e,  2+e,  e};
Physical Surface("xmax", 2) = Surface In BoundingBox{ 2-e, -2-e, -H-e,  2+e,  2+e,  e};
Physical Surface("ymin", 3) = Surface In BoundingBox{-2-e, -2-e, -H-e,  2+e, -2+e,  e};
Physical Surface("ymax", 4) = Surface In BoundingBox{-2-e,  2-e, -H-e,  2+e,  2+e,  e};
Physical Surface("bottom", 5) = Surface In BoundingBox{-2-e, -2-e, -H-e, 2+e, 2+e, -H+e};
Physical Surface("top", 6)    = Surface In BoundingBox{-2-e, -2-e,   -e, 2+e, 2+e,   e};
