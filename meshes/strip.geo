// Rectangular fabric strip [0, length] x [0, width] (lengths in m), meshed
// structured: nx divisions along x, ny along y; quadrilaterals when quads = 1
// (nx * ny of them), else two triangles per cell.
//
// Parameters (override through wff_mesh_options settings, which gmsh 4.8.4
// only sees as ONELAB numbers: hence the `Name` attribute on each).
DefineConstant[
  length = {0.254, Name "length"},
  width = {0.0254, Name "width"},
  nx = {64, Name "nx"},
  ny = {10, Name "ny"},
  quads = {1, Name "quads"}
];
If (length <= 0 || width <= 0 || nx < 1 || ny < 1 || nx != Round(nx) || ny != Round(ny))
  Error("strip.geo: need length, width > 0 and whole nx, ny >= 1 (length = %g, width = %g, nx = %g, ny = %g)",
        length, width, nx, ny);
EndIf

Point(1) = {0, 0, 0};
Point(2) = {length, 0, 0};
Point(3) = {length, width, 0};
Point(4) = {0, width, 0};

Line(1) = {1, 2};  // bottom, y = 0
Line(2) = {2, 3};  // right, x = length
Line(3) = {3, 4};  // top, y = width
Line(4) = {4, 1};  // left, x = 0

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Transfinite Curve {1, 3} = nx + 1;
Transfinite Curve {2, 4} = ny + 1;
Transfinite Surface {1} = {1, 2, 3, 4};
If (quads)
  Recombine Surface {1};
EndIf

Physical Curve("left", 1) = {4};
Physical Curve("right", 2) = {2};
Physical Curve("bottom", 3) = {1};
Physical Curve("top", 4) = {3};
Physical Surface("strip", 1) = {1};
