// exp, log, expm1 and log1p in double, which GLSL lacks (it has exp/log in float only; ALGORITHMS.md
// section 6). The casters accumulate opacity in double so that early ray termination decides exactly as the
// CPU reference does: in float, opacity near the threshold is off by 1e-7 and flips whether one more sample
// is composited. Small arguments are evaluated by series that involve no cancellation. Tested against the
// C library by numerics_test.comp.
#ifndef VR_NUMERICS_GLSL
#define VR_NUMERICS_GLSL

const double kLn2Hi = 6.93147180369123816490e-01LF;  // fdlibm's split of ln 2: k * kLn2Hi is exact
const double kLn2Lo = 1.90821492927058770002e-10LF;

// 1/n! for n = 0..16 and 1/k for odd k = 1..35: the series' coefficients.
const double kInverseFactorial[17] = double[17](
    1.0LF,
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
const double kInverseOdd[18] = double[18](
    1.0LF,
    0.3333333333333333LF,
    0.2LF,
    0.14285714285714285LF,
    0.1111111111111111LF,
    0.09090909090909091LF,
    0.07692307692307693LF,
    0.06666666666666667LF,
    0.058823529411764705LF,
    0.05263157894736842LF,
    0.047619047619047616LF,
    0.043478260869565216LF,
    0.04LF,
    0.037037037037037035LF,
    0.034482758620689655LF,
    0.03225806451612903LF,
    0.030303030303030304LF,
    0.02857142857142857LF);

// exp(x) - 1 for |x| <= 0.5: Taylor series to x^16 (truncation below 2e-18 relative).
double expm1Series(double x) {
    double p = kInverseFactorial[16];
    for (int n = 15; n >= 1; --n) p = p * x + kInverseFactorial[n];
    return p * x;
}

// 2 atanh(z) = log((1 + z) / (1 - z)) for |z| <= 1/3: odd series to z^35 (truncation below 2e-18 relative).
double atanh2Series(double z) {
    double z2 = z * z;
    double p = kInverseOdd[17];
    for (int i = 16; i >= 0; --i) p = p * z2 + kInverseOdd[i];
    return 2.0LF * z * p;
}

double vrExp(double x) {
    if (x < -746.0LF) return 0.0LF;
    if (x > 709.78LF) return 1.0LF / 0.0LF;
    double k = floor(x / (kLn2Hi + kLn2Lo) + 0.5LF);
    double r = (x - k * kLn2Hi) - k * kLn2Lo;  // |r| <= 0.35
    return ldexp(1.0LF + expm1Series(r), int(k));
}

// log(y) for y > 0: y = m 2^e with m in [sqrt(1/2), sqrt(2)), log m = 2 atanh((m - 1) / (m + 1)).
double vrLog(double y) {
    if (!(y > 0.0LF)) return y == 0.0LF ? -1.0LF / 0.0LF : 0.0LF / 0.0LF;
    if (isinf(y)) return y;
    int e;
    double m = frexp(y, e);
    if (m < 0.70710678118654752440LF) {
        m *= 2.0LF;
        e -= 1;
    }
    return double(e) * kLn2Hi + (double(e) * kLn2Lo + atanh2Series((m - 1.0LF) / (m + 1.0LF)));
}

// exp(x) - 1; beyond |x| <= 0.5, exp(x) - 1 loses at most a factor 2.6 of exp's accuracy.
double vrExpm1(double x) {
    if (abs(x) <= 0.5LF) return expm1Series(x);
    return vrExp(x) - 1.0LF;
}

// log(1 + x); for -0.5 <= x <= 1, log1p(x) = 2 atanh(x / (2 + x)) with |x / (2 + x)| <= 1/3.
double vrLog1p(double x) {
    if (x >= -0.5LF && x <= 1.0LF) return atanh2Series(x / (2.0LF + x));
    return vrLog(1.0LF + x);
}

#endif
