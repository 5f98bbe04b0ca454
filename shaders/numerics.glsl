// Float numerics the casters need and GLSL lacks (docs/ALGORITHMS.md sections 6 and 8): expm1, without which a
// span of tiny extinction has no opacity, and the optical depth as a pair of floats, whose sums agree to about
// 2^-44 relative however the samples are grouped into spans, so that early ray termination stops every caster at
// the same sample. Tested against double precision by numerics_test.comp. (No log is needed: the termination
// count works on the optical depth, whose threshold the host computes.)
#ifndef VR_NUMERICS_GLSL
#define VR_NUMERICS_GLSL

const float kInfinity = 1.0 / 0.0;

const float kLn2Hi = 6.9313812256e-01;  // fdlibm's split of ln 2: k * kLn2Hi is exact for |k| <= 128
const float kLn2Lo = 9.0580006145e-06;
const float kInvLn2 = 1.4426950216e+00;  // 1 / ln 2, rounded: only picks k

// exp(x) - 1 for |x| <= 0.5: x (1 + x/2! + ... + x^7/8!) by Estrin's scheme (truncation below 1.1e-8 relative),
// so the chain of dependent operations is 3 deep instead of Horner's 7: each caster iteration waits for it.
float expm1Series(float x) {
    float x2 = x * x, x4 = x2 * x2;
    float a0 = (1.0 + 0.5 * x) + (1.6666667e-01 + 4.1666668e-02 * x) * x2;
    float a1 = (8.3333338e-03 + 1.3888889e-03 * x) + (1.9841270e-04 + 2.4801587e-05 * x) * x2;
    return (a0 + a1 * x4) * x;
}

// exp(x) - 1 from one series: for |x| <= 0.5 the series of x itself (no cancellation), beyond it
// exp(x) - 1 with x = k ln 2 + r, |r| <= 0.35, which loses at most a factor 2.3 of the series' accuracy.
// llvmpipe runs both sides of every branch, so the two cases share the series rather than each having its own.
float vrExpm1(float x) {
    bool direct = abs(x) <= 0.5;
    float k = direct ? 0.0 : floor(x * kInvLn2 + 0.5);
    precise float r = direct ? x : (x - k * kLn2Hi) - k * kLn2Lo;
    float p = expm1Series(r);
    if (direct) return p;
    if (x < -88.0) return -1.0;
    if (x > 88.7) return kInfinity;
    return ldexp(1.0 + p, int(k)) - 1.0;
}

// A float pair (hi, lo) stands for hi + lo with |lo| at most half an ulp of hi. `precise` keeps every rounding
// these error-free transformations rely on.
vec2 twoSum(float a, float b) {
    precise float s = a + b;
    precise float bv = s - a;
    precise float e = (a - (s - bv)) + (b - bv);
    return vec2(s, e);
}

vec2 addPair(vec2 a, vec2 b) {
    vec2 s = twoSum(a.x, b.x);
    precise float lo = s.y + (a.y + b.y);
    precise float hi = s.x + lo;
    precise float e = lo - (hi - s.x);
    return vec2(hi, e);
}

// n x exactly (n an integer below 2^24): Dekker's product, with n split at 2^12 and x by Veltkamp's split, so each
// partial product has at most 24 significant bits.
vec2 exactProduct(float n, float x) {
    precise float p = n * x;
    precise float c = 4097.0 * x;
    precise float xHi = c - (c - x);
    precise float xLo = x - xHi;
    precise float nHi = floor(n * (1.0 / 4096.0)) * 4096.0;
    precise float nLo = n - nHi;
    precise float e = ((nHi * xHi - p) + nHi * xLo + nLo * xHi) + nLo * xLo;
    return vec2(p, e);
}

bool pairLess(vec2 a, vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// b - a rounded to a float (b may be +inf).
float pairDifference(vec2 b, vec2 a) {
    precise float d = (b.x - a.x) + (b.y - a.y);
    return d;
}

#endif
