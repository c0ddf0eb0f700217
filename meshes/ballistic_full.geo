// The whole ballistic specimen (fabric square side x side centred at the
// origin, clamped at radius >= radius), for an impact anywhere in the
// opening: lengths in m. The free fabric is the disk r < R; the clamped rest
// of the square is a second surface sharing the circle r = R. A mesh node
// sits at the impact point (impact_x, impact_y).
//
// Parameters (ONELAB numbers: the `Name` attribute on each, as in
// ballistic_quarter.geo):
//   h_min     element size at the impact point
//   h_max     element size from the circle outwards
//   radius    clamp opening radius R, m (0.127)
//   side      side of the square specimen, m (0.4)
//   impact_x, impact_y  the impact point, m (inside the opening)
// The size grows linearly with the distance to the impact point, from h_min
// there to h_max at a distance R; Mesh.MeshSizeFactor scales both.
DefineConstant[
  h_min = {0.0015, Name "h_min"},
  h_max = {0.008, Name "h_max"},
  radius = {0.127, Name "radius"},
  side = {0.4, Name "side"},
  impact_x = {0, Name "impact_x"},
  impact_y = {0, Name "impact_y"}
];
If (h_min <= 0 || h_max < h_min)
  Error("ballistic_full.geo: need 0 < h_min <= h_max (h_min = %g, h_max = %g)", h_min, h_max);
EndIf
If (radius <= 0 || side <= 2 * radius)
  Error("ballistic_full.geo: need 0 < radius < side / 2 (radius = %g, side = %g)", radius, side);
EndIf
If (impact_x^2 + impact_y^2 >= (radius - h_min)^2)
  Error("ballistic_full.geo: impact point (%g, %g) is not inside the opening of radius %g",
        impact_x, impact_y, radius);
EndIf

R = radius;
L = side / 2;

Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0};
Point(3) = {0, R, 0};
Point(4) = {-R, 0, 0};
Point(5) = {0, -R, 0};
Point(6) = {L, -L, 0};
Point(7) = {L, L, 0};
Point(8) = {-L, L, 0};
Point(9) = {-L, -L, 0};
Point(10) = {impact_x, impact_y, 0};

Circle(1) = {2, 1, 3};  // r = R, four quarter arcs
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Line(5) = {6, 7};       // x = L
Line(6) = {7, 8};       // y = L
Line(7) = {8, 9};       // x = -L
Line(8) = {9, 6};       // y = -L

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{10} In Surface{1};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2, 1};

Physical Curve("clamp_edge", 3) = {1, 2, 3, 4};  // r = R
Physical Curve("outer", 4) = {5, 6, 7, 8};       // the square's edges
Physical Surface("fabric", 1) = {1};
Physical Surface("clamp", 2) = {2};

Field[1] = Distance;
Field[1].PointsList = {10};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_min;
Field[2].SizeMax = h_max;
Field[2].DistMin = 0;
Field[2].DistMax = R;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
