#pragma once
// The studentized range distribution: ptukey / qtukey (Boost.Math 1.74 has none).
//
// Method of Copenhaver & Holland (1988), "Computation of the distribution of the maximum studentized
// range statistic with application to multiple significance testing of simple effects", J. Statist.
// Comput. Simul. 30, 1-15 -- the method behind R's ptukey/qtukey:
//   range of k standard normals:  W_k(w) = k * integral phi(z) [Phi(z + w) - Phi(z)]^(k-1) dz
//   studentized:  P(Q < q; k, nu) = integral_0^inf f_nu(s) W_k(q s) ds,
//   with s = sqrt(chi2_nu / nu), f_nu(s) = 2 (nu/2)^(nu/2) / Gamma(nu/2) s^(nu-1) exp(-nu s^2 / 2).
// Where Copenhaver & Holland use fixed 12- and 16-point Gauss-Legendre panels, both integrals here use
// Boost's adaptive Gauss-Kronrod (relative tolerance 1e-11), over z in [-9, 9] and over s between
// the 1e-18 quantiles of f_nu; nu = +infinity gives W_k directly. qtukey inverts ptukey with TOMS 748
// root bracketing to ~1e-13 relative (R iterates a secant to 1e-4 absolute from Gleason's start).
// Only one "range" (R's nranges = 1) is supported.

namespace crowdlab::analysis {

/// P(Q <= q) for k >= 2 means and nu > 0 error df (nu may be +infinity). q <= 0 gives 0.
double ptukey(double q, int nmeans, double df);
/// The q with ptukey(q, nmeans, df) = p, for 0 < p < 1. Throws InputError on bad arguments.
double qtukey(double p, int nmeans, double df);

}  // namespace crowdlab::analysis
