"""Welch's t-test per pixel and channel, at several scales, with a Šidák-corrected threshold.

Jung, Hanika & Dachsbacher, "Detecting Bias in Monte Carlo Renderers using Welch's t-test", JCGT 9(2),
2020: two independent estimates of a pixel, each a mean of n_i samples with sample variance s_i²,
  t = (m_1 − m_2) / sqrt(s_1²/n_1 + s_2²/n_2),
with the Welch–Satterthwaite degrees of freedom
  ν = (v_1 + v_2)² / (v_1²/(n_1 − 1) + v_2²/(n_2 − 1)),  v_i = s_i²/n_i,
and the two-sided p-value P(|T_ν| ≥ |t|) = I_{ν/(ν+t²)}(ν/2, 1/2) (regularised incomplete beta).
Mitsuba 3's test_renders.py runs the related z-test, which treats its reference as exact.

Beyond single pixels the test also runs on block means (a bias of 2 % is far below one pixel's noise
but not below the noise of a 16x16 block): a block's mean over k pixels has variance Σ v / k², and
its degrees of freedom follow from Welch–Satterthwaite over all its pixels. The Šidák threshold
  α_1 = 1 − (1 − α)^(1/m)
counts every test of every scale (m); tests at different scales are dependent, which only makes the
correction conservative.
"""
from __future__ import annotations

import numpy as np

SCALES = (1, 4, 16, 0)   # block sizes in pixels; 0 = the whole image

# Two estimates whose difference is below float precision are equal even when both variances are 0
# (e.g. a constant background): the variance of the difference is floored at (1e-5 · |m|)².
RELATIVE_FLOOR = 1e-5


def betacf(a, b, x, iterations=1000):
    """Continued fraction of the incomplete beta function (modified Lentz), vectorised over x, a."""
    tiny = 1e-300
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c = np.ones_like(x)
    d = 1.0 - qab * x / qap
    d = np.where(np.abs(d) < tiny, tiny, d)
    d = 1.0 / d
    h = d.copy()
    for m in range(1, iterations + 1):
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = np.where(np.abs(d) < tiny, tiny, d)
        c = 1.0 + aa / c
        c = np.where(np.abs(c) < tiny, tiny, c)
        d = 1.0 / d
        h *= d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = np.where(np.abs(d) < tiny, tiny, d)
        c = 1.0 + aa / c
        c = np.where(np.abs(c) < tiny, tiny, c)
        d = 1.0 / d
        delta = d * c
        h *= delta
        if np.all(np.abs(delta - 1.0) < 1e-13):
            break
    return h


def _lgamma(x):
    from math import lgamma
    return np.vectorize(lgamma, otypes=[float])(x)


def incomplete_beta(a, b, x):
    """Regularised incomplete beta I_x(a, b) for arrays a, x and scalar b (Numerical Recipes §6.4:
    the continued fraction converges for x < (a+1)/(a+b+2), else use I_x(a,b) = 1 − I_{1−x}(b,a))."""
    a = np.asarray(a, float)
    x = np.clip(np.asarray(x, float), 0.0, 1.0)
    b = np.full_like(a, float(b))
    with np.errstate(divide="ignore", invalid="ignore"):
        ln_front = (_lgamma(a + b) - _lgamma(a) - _lgamma(b) + a * np.log(x) + b * np.log1p(-x))
        front = np.exp(ln_front)
        direct = x < (a + 1.0) / (a + b + 2.0)
        xs = np.where(direct, x, 1.0 - x)
        aa, bb = np.where(direct, a, b), np.where(direct, b, a)
        cf = betacf(aa, bb, xs)
        out = np.where(direct, front * cf / a, 1.0 - front * cf / b)
    out = np.where(x <= 0.0, 0.0, np.where(x >= 1.0, 1.0, out))
    return np.clip(out, 0.0, 1.0)


NORMAL_DOF = 1e4   # above this many degrees of freedom T_ν is taken as standard normal


def normal_two_sided_p(t):
    """P(|Z| ≥ |t|) = erfc(|t|/√2)."""
    from math import erfc, sqrt
    return np.vectorize(lambda x: erfc(abs(x) / sqrt(2.0)), otypes=[float])(t)


def student_t_two_sided_p(t, dof):
    """P(|T_ν| ≥ |t|) = I_{ν/(ν+t²)}(ν/2, 1/2); the normal tail for ν > NORMAL_DOF (where the
    continued fraction needs O(√ν) terms)."""
    t, dof = np.broadcast_arrays(np.asarray(t, float), np.asarray(dof, float))
    small = dof <= NORMAL_DOF
    p = normal_two_sided_p(t)
    if np.any(small):
        p[small] = incomplete_beta(dof[small] / 2.0, 0.5, dof[small] / (dof[small] + t[small] ** 2))
    return p


def welch_p(m1, v1, n1, m2, v2, n2):
    """Two-sided p-values of Welch's test for means m_i with variances of the mean v_i and sample
    counts n_i (arrays of equal shape; n may be scalars or arrays)."""
    v = v1 + v2
    floor = (RELATIVE_FLOOR * np.maximum(np.abs(m1), np.abs(m2))) ** 2 + 1e-30
    v = np.maximum(v, floor)
    t = (m1 - m2) / np.sqrt(v)
    den = v1 * v1 / np.maximum(n1 - 1, 1) + v2 * v2 / np.maximum(n2 - 1, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        dof = np.where(den > 0, v * v / den, np.minimum(n1, n2) - 1.0)
    dof = np.clip(dof, 1.0, 1e7)
    return student_t_two_sided_p(t, dof)


def block_sums(img, k):
    """Sum over k x k blocks (k = 0: the whole image) of an H x W x C array; incomplete edge blocks
    are left out. Returns (blocks_y, blocks_x, C)."""
    h, w, c = img.shape
    if k == 0:
        return img.reshape(1, 1, h * w, c).sum(axis=2)
    by, bx = h // k, w // k
    return img[:by * k, :bx * k].reshape(by, k, bx, k, c).sum(axis=(1, 3))


def block_means(m1, v1, m2, v2, k):
    """Per k x k block: both means, both variances of the mean (Σ v / count²), the variance of their
    difference floored as in welch_p, and the pixel count."""
    count = block_sums(np.ones_like(m1), k)
    bm1, bm2 = block_sums(m1, k) / count, block_sums(m2, k) / count
    bv1, bv2 = block_sums(v1, k) / count ** 2, block_sums(v2, k) / count ** 2
    v = np.maximum(bv1 + bv2, (RELATIVE_FLOOR * np.maximum(np.abs(bm1), np.abs(bm2))) ** 2 + 1e-30)
    return bm1, bm2, bv1, bv2, v, count


def block_welch_p(m1, v1, n1, m2, v2, n2, k):
    """Welch p-values of k x k block means; v, n per pixel (n broadcast to the image)."""
    n1 = np.broadcast_to(np.asarray(n1, float), m1.shape)
    n2 = np.broadcast_to(np.asarray(n2, float), m2.shape)
    bm1, bm2, bv1, bv2, v, count = block_means(m1, v1, m2, v2, k)
    # Welch–Satterthwaite for a sum of independent terms: ν = (Σ v)² / Σ v²/(n−1), scaled like v.
    d1 = block_sums(v1 * v1 / np.maximum(n1 - 1, 1), k) / count ** 4
    d2 = block_sums(v2 * v2 / np.maximum(n2 - 1, 1), k) / count ** 4
    with np.errstate(divide="ignore", invalid="ignore"):
        dof = np.where(d1 + d2 > 0, (bv1 + bv2) ** 2 / (d1 + d2), np.minimum(n1.min(), n2.min()) - 1.0)
    dof = np.clip(dof, 1.0, 1e7)
    return student_t_two_sided_p((bm1 - bm2) / np.sqrt(v), dof)


def floor_by_reference(v1, n1, v2, n2):
    """The test image's variance of the mean, bounded below by the reference's per-sample variance
    over n1: max(v1, v2·n2/n1). Welch's test assumes each sample variance is a fair estimate; at a
    pixel where a rare event carries the mean (a silhouette covering 0.3 % of the pixel, a small
    highlight) a sample of a few hundred often has seen none and reports almost no variance, and
    the pixel is rejected though nothing is biased. The reference's much larger sample estimates
    that variance well; under the null hypothesis both renderers estimate the same integral, and
    a lower bound from it can only make the test more conservative, never reject more."""
    return np.maximum(v1, v2 * np.asarray(n2, float) / np.asarray(n1, float))


def sidak_threshold(alpha, tests):
    """Per-test level α_1 = 1 − (1 − α)^(1/m), computed without cancellation."""
    return -np.expm1(np.log1p(-alpha) / tests)


def multiscale_test(m1, v1, n1, m2, v2, n2, alpha=0.01, scales=SCALES):
    """Welch's test at every scale. Returns dict: p_min, threshold, tests, scale (block size of the
    smallest p; 0 = whole image), per_scale {k: p array}, and pixel p-values."""
    per_scale = {k: block_welch_p(m1, v1, n1, m2, v2, n2, k) if k != 1 else welch_p(m1, v1, n1, m2, v2, n2)
                 for k in scales if k <= min(m1.shape[:2])}   # no block larger than the image
    tests = sum(p.size for p in per_scale.values())
    threshold = sidak_threshold(alpha, tests)
    scale, p_min = min(((k, float(np.min(p))) for k, p in per_scale.items()), key=lambda kp: kp[1])
    return {"p_min": p_min, "threshold": float(threshold), "tests": tests, "scale": scale,
            "per_scale": per_scale, "passed": p_min > threshold}


def mitsuba_z_test(mean, n, ref_mean, ref_sample_var, alpha=0.01, variance_floor=1e-4, accept_fraction=0.9975):
    """Mitsuba 3's own acceptance rule (src/render/tests/test_renders.py, z_test and test_render),
    for comparison with the stricter test above: per pixel and channel
      z = |mean − ref| · sqrt(n / max(ref_sample_var, 1e-4)),  p = 2 (1 − Φ(z)),
    the reference treated as exact and its per-sample variance floored at 1e-4; the Šidák level over
    the pixel count only (α₁ = 1 − (1 − α)^(1/pixels)); the render passes when at least 99.75 % of
    the pixels' tests do (count of passing channel tests / 3 ≥ 0.9975 · pixels). Returns (passed,
    fraction of passing tests, smallest p)."""
    pixels = mean.shape[0] * mean.shape[1]
    z = np.abs(mean - ref_mean) * np.sqrt(n / np.maximum(ref_sample_var, variance_floor))
    p = normal_two_sided_p(z)
    level = sidak_threshold(alpha, pixels)
    passing = np.count_nonzero(p > level)
    return bool(passing / 3 >= accept_fraction * pixels), float(passing / p.size), float(np.min(p))


def block_t_and_ratio(m1, v1, m2, v2, k, bx, by):
    """The t statistic and mean ratio m1/m2 per channel of one k x k block (k = 0: the whole
    image) at block column bx, row by; v are variances of the per-pixel means."""
    bm1, bm2, _, _, v, _ = block_means(m1, v1, m2, v2, k)
    a, b, v = bm1[by, bx], bm2[by, bx], v[by, bx]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(b != 0, a / b, np.nan)
    return (a - b) / np.sqrt(v), ratio
