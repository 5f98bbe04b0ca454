// expm1 and log1p in float, which GLSL lacks (ALGORITHMS.md section 6). The cancellation in exp(x) - 1 and
// log(1 + x) for small |x| turns the few-ulp error of GLSL's exp/log into large relative errors, so the small
// range is evaluated by series that involve no cancellation. Tested against double by numerics_test.comp.
#ifndef VR_NUMERICS_GLSL
#define VR_NUMERICS_GLSL

// exp(x) - 1. |x| < 0.5: Taylor series to x^10 (truncation below 3e-10 relative); beyond, exp(x) - 1 loses
// at most a factor 2.6 of exp's accuracy.
float vrExpm1(float x) {
    if (abs(x) < 0.5) {
        float p = 1.0 / 3628800.0;
        p = fma(p, x, 1.0 / 362880.0);
        p = fma(p, x, 1.0 / 40320.0);
        p = fma(p, x, 1.0 / 5040.0);
        p = fma(p, x, 1.0 / 720.0);
        p = fma(p, x, 1.0 / 120.0);
        p = fma(p, x, 1.0 / 24.0);
        p = fma(p, x, 1.0 / 6.0);
        p = fma(p, x, 0.5);
        p = fma(p, x, 1.0);
        return p * x;
    }
    return exp(x) - 1.0;
}

// log(1 + x). -0.5 <= x <= 1: log1p(x) = 2 atanh(z), z = x / (2 + x) in [-1/3, 1/3], by its odd series to z^17
// (truncation below 1e-9 relative); beyond, 1 + x carries no cancellation.
float vrLog1p(float x) {
    if (x >= -0.5 && x <= 1.0) {
        float z = x / (2.0 + x);
        float z2 = z * z;
        float p = 1.0 / 17.0;
        p = fma(p, z2, 1.0 / 15.0);
        p = fma(p, z2, 1.0 / 13.0);
        p = fma(p, z2, 1.0 / 11.0);
        p = fma(p, z2, 1.0 / 9.0);
        p = fma(p, z2, 1.0 / 7.0);
        p = fma(p, z2, 1.0 / 5.0);
        p = fma(p, z2, 1.0 / 3.0);
        p = fma(p, z2, 1.0);
        return 2.0 * z * p;
    }
    return log(1.0 + x);
}

#endif
