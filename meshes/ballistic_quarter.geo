// Quarter model of the ballistic specimen (fabric square side x side,
// clamped at radius >= radius, impact at the centre): x, y >= 0, lengths in m.
// (meshes/ballistic_full.geo: the whole square, for an impact off the centre.)
// The free fabric is the quarter disk r < R; the clamped rest of the square
// is a second surface sharing the arc r = R.
//
// Parameters (override through wff_mesh_options settings, which gmsh 4.8.4
// only sees as ONELAB numbers: hence the `Name` attribute on each):
//   h_min    element size at the impact point (0, 0)
//   h_max    element size from the arc outwards (arc and clamp region)
//   h_clamp  element size in the clamp region (0: h_max; < h_max refines the
//            clamp region only, from the arc outwards)
//   radius   clamp opening radius R, m (0.127)
//   side     side of the square specimen, m (0.4)
//   frame    half side of the clamping frames (the experiment's 30.5 cm
//            wooden frame and aluminium plates: 0.1525); 0: none (the
//            default). With R < frame < L the clamp region is split at the
//            square of that half side: "clamp" is the fabric under the frames
//            (R <= r, |x|, |y| <= frame), "margin" the fabric outside them, and
//            the physical curve "staples" is the frame's outer edge
//            (x = frame or y = frame), where the specimen is stapled.
// The size grows linearly with the distance to (0, 0), from h_min at 0 to
// h_max at r = R; Mesh.MeshSizeFactor scales both. The defaults give 2288
// triangles (1259 in the fabric) with gmsh 4.8.4; the paper's quarter model
// had 2308.
DefineConstant[
  h_min = {0.0015, Name "h_min"},
  h_max = {0.008, Name "h_max"},
  h_clamp = {0, Name "h_clamp"},
  frame = {0, Name "frame"},
  radius = {0.127, Name "radius"},
  side = {0.4, Name "side"}
];
If (h_min <= 0 || h_max < h_min)
  Error("ballistic_quarter.geo: need 0 < h_min <= h_max (h_min = %g, h_max = %g)", h_min, h_max);
EndIf
If (h_clamp < 0 || h_clamp > h_max)
  Error("ballistic_quarter.geo: need 0 <= h_clamp <= h_max (h_clamp = %g, h_max = %g)", h_clamp, h_max);
EndIf

If (radius <= 0 || side <= 2 * radius)
  Error("ballistic_quarter.geo: need 0 < radius < side / 2 (radius = %g, side = %g)", radius, side);
EndIf
R = radius;    // clamp radius
L = side / 2;  // half side of the square specimen

Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0};
Point(3) = {0, R, 0};
Point(4) = {L, 0, 0};
Point(5) = {L, L, 0};
Point(6) = {0, L, 0};

Line(1) = {1, 2};       // y = 0, fabric part
Circle(2) = {2, 1, 3};  // r = R
Line(3) = {3, 1};       // x = 0, fabric part
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Surface("fabric", 1) = {1};
Physical Curve("clamp_edge", 3) = {2};    // r = R

If (frame == 0)
  Line(4) = {2, 4};       // y = 0, clamp part
  Line(5) = {4, 5};       // x = L
  Line(6) = {5, 6};       // y = L
  Line(7) = {6, 3};       // x = 0, clamp part
  Curve Loop(2) = {4, 5, 6, 7, -2};
  Plane Surface(2) = {2};
  Physical Curve("sym_x", 1) = {3, 7};      // x = 0: u_x = 0
  Physical Curve("sym_y", 2) = {1, 4};      // y = 0: u_y = 0
  Physical Curve("outer", 4) = {5, 6};      // x = L and y = L
  Physical Surface("clamp", 2) = {2};
Else
  If (frame <= R || frame >= L)
    Error("ballistic_quarter.geo: need R < frame < L (frame = %g, R = %g, L = %g)", frame, R, L);
  EndIf
  Point(7) = {frame, 0, 0};
  Point(8) = {frame, frame, 0};
  Point(9) = {0, frame, 0};
  Line(4) = {2, 7};       // y = 0, under the frames
  Line(8) = {7, 8};       // x = frame: the staple line
  Line(9) = {8, 9};       // y = frame: the staple line
  Line(10) = {9, 3};      // x = 0, under the frames
  Line(11) = {7, 4};      // y = 0, margin
  Line(5) = {4, 5};       // x = L
  Line(6) = {5, 6};       // y = L
  Line(12) = {6, 9};      // x = 0, margin
  Curve Loop(2) = {4, 8, 9, 10, -2};
  Plane Surface(2) = {2};
  Curve Loop(3) = {11, 5, 6, 12, -9, -8};
  Plane Surface(3) = {3};
  Physical Curve("sym_x", 1) = {3, 10, 12};
  Physical Curve("sym_y", 2) = {1, 4, 11};
  Physical Curve("outer", 4) = {5, 6};
  Physical Curve("staples", 5) = {8, 9};
  Physical Surface("clamp", 2) = {2};
  Physical Surface("margin", 3) = {3};
EndIf

// Size field only (no point sizes, no extension from the boundary), so the
// grading is the same along the symmetry lines and inside the disk.
Field[1] = Distance;
Field[1].PointsList = {1};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_min;
Field[2].SizeMax = h_max;
Field[2].DistMin = 0;
Field[2].DistMax = R;
If (h_clamp > 0 && h_clamp < h_max)
  // h_clamp from r = R outwards (the fabric's grading inside r < R unchanged)
  Field[3] = Threshold;
  Field[3].InField = 1;
  Field[3].SizeMin = h_max;
  Field[3].SizeMax = h_clamp;
  Field[3].DistMin = R - 1e-9;
  Field[3].DistMax = R;
  Field[4] = Min;
  Field[4].FieldsList = {2, 3};
  Background Field = 4;
Else
  Background Field = 2;
EndIf
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
