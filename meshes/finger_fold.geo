// A soft finger with two joints: 2 x 2 cm section, L long along z, its base at z = 0. At each joint
// (z = z1, z2) a notch across the inner (-x) side: a V of opening "angle" degrees whose apex ends
// in a round hole of radius r at x = -0.01 + depth (a flexure hinge's keyhole), leaving a ligament
// on the outer side. The joint bends towards -x until the V's two faces meet. The hole spreads the
// bending over the ligament and keeps the faces apart along the surface where they meet: a sharp
// V's faces meet at its apex, within self-contact's ring (-contact_self_ring) of each other
// (input/finger_fold.opts, docs/scenes.md). Unstructured linear tetrahedra, lc away from the
// joints, lc_joint at them. Units: metres.
//   gmsh -3 -setnumber lc 0.005 -setnumber lc_joint 0.0035 -setnumber r 0.0025 finger_fold.geo -o finger_fold.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.005, Name "Parameters/lc"]; EndIf
If (!Exists(lc_joint)) lc_joint = DefineNumber[0.0035, Name "Parameters/lc_joint"]; EndIf
If (!Exists(L)) L = DefineNumber[0.11, Name "Parameters/L"]; EndIf
If (!Exists(depth)) depth = DefineNumber[0.01, Name "Parameters/depth"]; EndIf
If (!Exists(r)) r = DefineNumber[0.0025, Name "Parameters/r"]; EndIf
If (!Exists(angle)) angle = DefineNumber[40, Name "Parameters/angle"]; EndIf
If (!Exists(z1)) z1 = DefineNumber[0.05, Name "Parameters/z1"]; EndIf
If (!Exists(z2)) z2 = DefineNumber[0.08, Name "Parameters/z2"]; EndIf
a = 0.01;
Box(1) = {-a, -a, 0, 2 * a, 2 * a, L};
// each notch: a triangular prism across y, its apex line at x = -a + depth, its mouth 1 mm beyond
// the face x = -a (a clean cut), and a cylinder of radius r along y on the apex line
t = Tan(angle * Pi / 360);
zs[] = {z1, z2};
For i In {0 : #zs[] - 1}
  zc = zs[i];
  p1 = newp; Point(p1) = {-a + depth, -a - 0.001, zc};
  p2 = newp; Point(p2) = {-a - 0.001, -a - 0.001, zc - (depth + 0.001) * t};
  p3 = newp; Point(p3) = {-a - 0.001, -a - 0.001, zc + (depth + 0.001) * t};
  l1 = newl; Line(l1) = {p1, p2};
  l2 = newl; Line(l2) = {p2, p3};
  l3 = newl; Line(l3) = {p3, p1};
  ll = newll; Curve Loop(ll) = {l1, l2, l3};
  s = news; Plane Surface(s) = {ll};
  ex[] = Extrude {0, 2 * a + 0.002, 0} { Surface{s}; };
  cut[2 * i] = ex[1];
  cut[2 * i + 1] = newv;
  Cylinder(cut[2 * i + 1]) = {-a + depth, -a - 0.001, zc, 0, 2 * a + 0.002, 0, r};
EndFor
BooleanDifference(100) = { Volume{1}; Delete; }{ Volume{cut[]}; Delete; };
Mesh.CharacteristicLengthMin = lc_joint;
Mesh.CharacteristicLengthMax = lc;
For i In {0 : #zs[] - 1}
  Field[i + 1] = Box;
  Field[i + 1].VIn = lc_joint;
  Field[i + 1].VOut = lc;
  Field[i + 1].XMin = -a - 0.001;
  Field[i + 1].XMax = -a + depth + r + 0.002;
  Field[i + 1].YMin = -a - 0.001;
  Field[i + 1].YMax = a + 0.001;
  Field[i + 1].ZMin = zs[i] - (depth + 0.001) * t - 0.001;
  Field[i + 1].ZMax = zs[i] + (depth + 0.001) * t + 0.001;
  Field[i + 1].Thickness = 0.004;
EndFor
Field[10] = Min;
Field[10].FieldsList = {1, 2};
Background Field = 10;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.ElementOrder = 1;
e = 1e-6;
Physical Volume("finger", 1) = {100};
Physical Surface("base", 1) = Surface In BoundingBox{-a-e, -a-e, -e, a+e, a+e, e};
Physical Surface("tip", 2) = Surface In BoundingBox{-a-e, -a-e, L-e, a+e, a+e, L+e};
