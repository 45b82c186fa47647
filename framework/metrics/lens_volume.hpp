#pragma once
// Analytic intersection volumes used as ground truth for the overlap measure.
//   lens_volume(r1, r2, d): volume (m^3) of the intersection of two balls of radii r1, r2 (metres)
//     whose centres are d metres apart. Formula: V = pi (r1 + r2 - d)^2 (d^2 + 2 d (r1 + r2)
//     - 3 (r1 - r2)^2) / (12 d) (Weisstein, "Sphere-Sphere Intersection", MathWorld, Eq. 16).
//     d >= r1 + r2 -> 0; d <= |r1 - r2| -> volume of the smaller ball.
//   circle_lens_area(r1, r2, d): area (m^2) of the intersection of two discs (the cross-section of
//     two parallel cylinders), by the standard circular-segment formula
//     A = r1^2 acos(d1 / r1) - d1 sqrt(r1^2 - d1^2) + r2^2 acos(d2 / r2) - d2 sqrt(r2^2 - d2^2),
//     d1 = (d^2 + r1^2 - r2^2) / (2 d), d2 = d - d1.
// Throws InputError for negative or non-finite arguments.
namespace crowdlab {

double lens_volume(double r1, double r2, double d);
double circle_lens_area(double r1, double r2, double d);

}  // namespace crowdlab
