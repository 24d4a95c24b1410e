// Flat punch (input/flat_punch.opts, tests/test_flat_punch.py): a block x in [-0.15,0.15], y in [-0.07,0.07],
// z in [-0.05,0] (top face z = 0, the contact face), a structured grid of linear tetrahedra (extruded
// layers, each hexahedral cell split into 6 tets) graded finer under the punch's path: cells of d in x over
// [-xs,xs] and in y over [-ys,ys], three coarser cells on each side; in z, from the top down, nzt cells of
// dzt, then two cells to z = -0.025 and one to the bottom. Units: metres.
// The grid lines of the path lie at multiples of d (xs, ys multiples of d): with d = 8 mm, the faces of the scene's
// 6 cm punch, its centre at x = -0.08 + 0.004 k, lie at x = 2 mm (mod 4 mm) and never end a step within 2 mm of a
// vertex column, nor its sides (y = +-0.03) within 2 mm of a row. A vertex that ends a step just behind the
// punch's leading face, above its bottom, has that face for its nearest feature and is pushed ahead by it
// (ploughed, at the box's sharp edge) instead of passing under it (docs/scenes.md, "Flat punch").
//   gmsh -3 -setnumber d 0.008 punch_block.geo -o punch_block.msh
If (!Exists(d)) d = DefineNumber[0.008, Name "Parameters/d"]; EndIf
If (!Exists(xs)) xs = DefineNumber[0.12, Name "Parameters/xs"]; EndIf
If (!Exists(ys)) ys = DefineNumber[0.032, Name "Parameters/ys"]; EndIf
If (!Exists(nzt)) nzt = DefineNumber[2, Name "Parameters/nzt"]; EndIf
If (!Exists(dzt)) dzt = DefineNumber[0.0045, Name "Parameters/dzt"]; EndIf
L = 0.15; W = 0.07; H = 0.05;
nx = Round(2 * xs / d); ny = Round(2 * ys / d);

Point(1) = {-L, -W, -H};
// extrusions of a point, a line and a surface with layers: x, then y, then z (from the bottom up)
ex[] = Extrude {2 * L, 0, 0} { Point{1}; Layers{ {3, nx, 3}, {(L - xs) / (2 * L), (L + xs) / (2 * L), 1} }; };
ey[] = Extrude {0, 2 * W, 0} { Line{ex[1]}; Layers{ {3, ny, 3}, {(W - ys) / (2 * W), (W + ys) / (2 * W), 1} }; };
zt = nzt * dzt;
ez[] = Extrude {0, 0, H} { Surface{ey[1]}; Layers{ {1, 2, nzt}, {(H - 0.025) / H, (H - zt) / H, 1} }; };
Mesh.ElementOrder = 1;

e = 1e-6;
Physical Volume("body", 1) = {ez[1]};
Physical Surface("xmin", 1) = Surface In BoundingBox{-L-e, -W-e, -H-e, -L+e,  W+e,  e};
Physical Surface("xmax", 2) = Surface In BoundingBox{ L-e, -W-e, -H-e,  L+e,  W+e,  e};
Physical Surface("ymin", 3) = Surface In BoundingBox{-L-e, -W-e, -H-e,  L+e, -W+e,  e};
Physical Surface("ymax", 4) = Surface In BoundingBox{-L-e,  W-e, -H-e,  L+e,  W+e,  e};
Physical Surface("bottom", 5) = Surface In BoundingBox{-L-e, -W-e, -H-e, L+e, W+e, -H+e};
Physical Surface("top", 6)    = Surface In BoundingBox{-L-e, -W-e,   -e, L+e, W+e,   e};
