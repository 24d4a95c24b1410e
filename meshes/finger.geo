// A soft finger: 2 x 2 cm section, 10 cm long along z, its base at z = 0 (input/finger_push.opts).
// Unstructured linear tetrahedra. Units: metres.
//   gmsh -3 -setnumber lc 0.004 finger.geo -o finger.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.004, Name "Parameters/lc"]; EndIf
Box(1) = {-0.01, -0.01, 0, 0.02, 0.02, 0.1};
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
e = 1e-6;
Physical Volume("finger", 1) = {1};
Physical Surface("base", 1) = Surface In BoundingBox{-0.01-e, -0.01-e, -e, 0.01+e, 0.01+e, e};
Physical Surface("tip", 2) = Surface In BoundingBox{-0.01-e, -0.01-e, 0.1-e, 0.01+e, 0.01+e, 0.1+e};
Physical Point("tip_corner", 3) = Point In BoundingBox{0.01-e, 0.01-e, 0.1-e, 0.01+e, 0.01+e, 0.1+e};
