// expm1 in double, which GLSL lacks (it has exp in float only; docs/ALGORITHMS.md section 6). The casters accumulate
// opacity in double so that early ray termination decides exactly as the CPU reference does: in float, opacity
// near the threshold is off by 1e-7 and flips whether one more sample is composited. Small arguments are
// evaluated by a series that involves no cancellation. Tested against the C library by numerics_test.comp. (No
// log is needed: the termination count works on the optical depth, whose threshold the host computes.)
#ifndef VR_NUMERICS_GLSL
#define VR_NUMERICS_GLSL

const double kLn2Hi = 6.93147180369123816490e-01LF;  // fdlibm's split of ln 2: k * kLn2Hi is exact
const double kLn2Lo = 1.90821492927058770002e-10LF;
const double kInvLn2 = 1.44269504088896338700e+00LF;  // 1 / ln 2, rounded: only picks k

// The series' coefficients: 1/n! for n = 1..16.
const double kInverseFactorial[16] = double[16](
    1.0LF,
    0.5LF,
    0.16666666666666666LF,
    0.041666666666666664LF,
    0.008333333333333333LF,
    0.001388888888888889LF,
    0.0001984126984126984LF,
    2.48015873015873e-05LF,
    2.7557319223985893e-06LF,
    2.755731922398589e-07LF,
    2.505210838544172e-08LF,
    2.08767569878681e-09LF,
    1.6059043836821613e-10LF,
    1.1470745597729725e-11LF,
    7.647163731819816e-13LF,
    4.779477332387385e-14LF);
// c[0] + c[1] x + ... + c[15] x^15 by Estrin's scheme: pairs, then pairs of pairs, so the chain of dependent
// operations is 4 multiply-adds deep instead of Horner's 15. llvmpipe runs one batch of rays at a time, and
// each caster iteration waits for this chain (the span's expm1).
double series16(double c[16], double x) {
    double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
    double a0 = (c[0] + c[1] * x) + (c[2] + c[3] * x) * x2;
    double a1 = (c[4] + c[5] * x) + (c[6] + c[7] * x) * x2;
    double a2 = (c[8] + c[9] * x) + (c[10] + c[11] * x) * x2;
    double a3 = (c[12] + c[13] * x) + (c[14] + c[15] * x) * x2;
    return (a0 + a1 * x4) + (a2 + a3 * x4) * x8;
}

// exp(x) - 1 for |x| <= 0.5: Taylor series to x^16 (truncation below 2e-19 relative).
double expm1Series(double x) { return series16(kInverseFactorial, x) * x; }

// exp(x) - 1 from one series: for |x| <= 0.5 the series of x itself (no cancellation), beyond it
// exp(x) - 1 with x = k ln 2 + r, |r| <= 0.35, which loses at most a factor 2.6 of exp's accuracy. llvmpipe
// runs both sides of every branch, so the two cases share the series rather than each having its own.
double vrExpm1(double x) {
    bool direct = abs(x) <= 0.5LF;
    double k = direct ? 0.0LF : floor(x * kInvLn2 + 0.5LF);
    double r = direct ? x : (x - k * kLn2Hi) - k * kLn2Lo;
    double p = expm1Series(r);
    if (direct) return p;
    if (x < -746.0LF) return -1.0LF;
    if (x > 709.78LF) return 1.0LF / 0.0LF;
    return ldexp(1.0LF + p, int(k)) - 1.0LF;
}

#endif
