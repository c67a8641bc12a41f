// Elementary functions from +, -, *, / and sqrt only. glibc picks its pow/atan/sin variants at
// run time by CPU (FMA or not) and they are not correctly rounded, so a pixel could change
// from one machine to the next; these give the same bits on every x86-64 (with
// -ffp-contract=off). Accuracy ~1e-9 relative, far below what 8-bit output can show.
#pragma once

namespace msr {

constexpr double kPiD = 3.14159265358979323846;

// atan(t) for t in [0, 1].
inline double det_atan01(double t) {
    const double k1_sqrt3 = 0.57735026918962576451;  // tan(pi/6)
    double base = 0.0;
    if (t > 0.26794919243112270) {  // tan(pi/12): shift by pi/6 to keep |t| small
        t = (t - k1_sqrt3) / (1.0 + t * k1_sqrt3);
        base = kPiD / 6.0;
    }
    double t2 = t * t;
    // Taylor series to t^15 (|t| <= 0.268: remainder < 1e-10).
    double p = 1.0 / 15.0;
    p = 1.0 / 13.0 - t2 * p;
    p = 1.0 / 11.0 - t2 * p;
    p = 1.0 / 9.0 - t2 * p;
    p = 1.0 / 7.0 - t2 * p;
    p = 1.0 / 5.0 - t2 * p;
    p = 1.0 / 3.0 - t2 * p;
    p = 1.0 - t2 * p;
    return base + t * p;
}

inline double det_atan2(double y, double x) {
    double ax = x < 0 ? -x : x, ay = y < 0 ? -y : y;
    if (ax == 0.0 && ay == 0.0) return 0.0;
    double a = ay <= ax ? det_atan01(ay / ax) : kPiD / 2.0 - det_atan01(ax / ay);
    if (x < 0) a = kPiD - a;
    return y < 0 ? -a : a;
}

// sin and cos of a in [-4 pi, 4 pi] (more than the renderer needs).
inline void det_sincos(double a, double &s, double &c) {
    const double half_pi = kPiD / 2.0;
    double q = a / half_pi;
    long k = long(q < 0 ? q - 0.5 : q + 0.5);
    double r = a - double(k) * half_pi;  // |r| <= pi/4
    double r2 = r * r;
    // Taylor series to r^13 / r^14 (remainder < 1e-12 for |r| <= pi/4).
    double sp = r * (1.0 - r2 / 6.0 * (1.0 - r2 / 20.0 * (1.0 - r2 / 42.0 * (1.0 - r2 / 72.0 * (1.0 - r2 / 110.0 * (1.0 - r2 / 156.0))))));
    double cp = 1.0 - r2 / 2.0 * (1.0 - r2 / 12.0 * (1.0 - r2 / 30.0 * (1.0 - r2 / 56.0 * (1.0 - r2 / 90.0 * (1.0 - r2 / 132.0 * (1.0 - r2 / 182.0))))));
    switch (((k % 4) + 4) % 4) {
    case 0: s = sp; c = cp; break;
    case 1: s = cp; c = -sp; break;
    case 2: s = -sp; c = -cp; break;
    default: s = -cp; c = sp; break;
    }
}

inline void det_sincos_deg(double deg, double &s, double &c) { det_sincos(deg * (kPiD / 180.0), s, c); }

}  // namespace msr
