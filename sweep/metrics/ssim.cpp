#include "sweep/metrics/ssim.h"

#include <array>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "sweep/metrics/colour.h"
#include "sweep/metrics/rmse.h"

namespace vr {

namespace {

std::vector<double> lumaOf(const Image& im) {
    std::vector<double> y(std::size_t(im.width) * im.height);
    for (std::size_t p = 0; p < y.size(); ++p)
        y[p] = luminance(im.rgba[p * 4], im.rgba[p * 4 + 1], im.rgba[p * 4 + 2]);
    return y;
}

std::array<double, kSsimWindow> gaussianWeights() {
    std::array<double, kSsimWindow> w;
    double sum = 0;
    for (int i = 0; i < kSsimWindow; ++i) {
        const double d = i - kSsimWindow / 2;
        sum += w[i] = std::exp(-d * d / (2 * kSsimSigma * kSsimSigma));
    }
    for (double& x : w) x /= sum;
    return w;
}

// Separable Gaussian filter over the valid positions: out is (w - 10) x (h - 10).
std::vector<double> blur(const std::vector<double>& in, int w, int h) {
    static const std::array<double, kSsimWindow> g = gaussianWeights();
    const int ow = w - kSsimWindow + 1, oh = h - kSsimWindow + 1;
    std::vector<double> rows(std::size_t(ow) * h), out(std::size_t(ow) * oh);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < ow; ++x) {
            double s = 0;
            for (int k = 0; k < kSsimWindow; ++k) s += g[k] * in[std::size_t(y) * w + x + k];
            rows[std::size_t(y) * ow + x] = s;
        }
    for (int y = 0; y < oh; ++y)
        for (int x = 0; x < ow; ++x) {
            double s = 0;
            for (int k = 0; k < kSsimWindow; ++k) s += g[k] * rows[std::size_t(y + k) * ow + x];
            out[std::size_t(y) * ow + x] = s;
        }
    return out;
}

}  // namespace

double ssim(const Image& reference, const Image& image) {
    requireSameSize(reference, image);
    const int w = image.width, h = image.height;
    if (w < kSsimWindow || h < kSsimWindow)
        throw InputError("SSIM needs images of at least 11x11 pixels, not " + std::to_string(w) + "x" +
                         std::to_string(h));
    const std::vector<double> a = lumaOf(reference), b = lumaOf(image);
    std::vector<double> aa(a.size()), bb(a.size()), ab(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        aa[i] = a[i] * a[i];
        bb[i] = b[i] * b[i];
        ab[i] = a[i] * b[i];
    }
    const std::vector<double> mu1 = blur(a, w, h), mu2 = blur(b, w, h), s11 = blur(aa, w, h),
                              s22 = blur(bb, w, h), s12 = blur(ab, w, h);
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double sum = 0;
    for (std::size_t i = 0; i < mu1.size(); ++i) {
        const double m1 = mu1[i], m2 = mu2[i];
        const double v1 = s11[i] - m1 * m1, v2 = s22[i] - m2 * m2, cov = s12[i] - m1 * m2;
        sum += (2 * m1 * m2 + c1) * (2 * cov + c2) / ((m1 * m1 + m2 * m2 + c1) * (v1 + v2 + c2));
    }
    return sum / double(mu1.size());
}

}  // namespace vr
