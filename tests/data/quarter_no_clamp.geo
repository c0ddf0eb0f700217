// Quarter disk of the ballistic specimen WITHOUT a "clamp" group (only sym_x,
// sym_y, rim and fabric): the ballistic scene must stop with a message naming
// the missing group (tests/sh/bad_input.sh). Coarse: ~100 triangles.
R = 0.127;
Point(1) = {0, 0, 0, 0.02};
Point(2) = {R, 0, 0, 0.02};
Point(3) = {0, R, 0, 0.02};
Line(1) = {1, 2};
Circle(2) = {2, 1, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Curve("sym_x", 1) = {3};
Physical Curve("sym_y", 2) = {1};
Physical Curve("rim", 3) = {2};
Physical Surface("fabric", 4) = {1};
