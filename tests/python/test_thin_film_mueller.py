"""iris.thin_film.stack_mueller: a stack's reflection Mueller matrix equals |r_s|², |r_p|² and
Re / Im of r_s r_p* of an independent transfer matrix written here in NumPy (Born & Wolf §1.6.2
characteristic matrices, e^{−iωt}, the tangential-H form of p) to 1e-12; the response to
unpolarized light is stack_rt's R and T; coherent stacks are pure (C² + D² = P_s P_p), the
incoherent sum depolarizes; arguments broadcast like stack_rt's; bad input raises."""
import unittest

from support import iris, np


def naive_r(lam, cos_i, n0, layers, sub):
    """(r_s, r_p) of the stack, independently: characteristic matrices per layer, multiplied top to
    bottom, r = (y0 B − C) / (y0 B + C) with (B, C) = M (1, y_sub) (Macleod ch. 2 with i → −i)."""
    s = n0 * np.sqrt(1 - cos_i * cos_i)

    def q(n):
        v = np.sqrt(complex(n) ** 2 - s * s)
        return -v if v.imag < 0 or (v.imag == 0 and v.real < 0) else v

    out = []
    for pol in (0, 1):
        def y(n):
            return q(n) if pol == 0 else q(n) / complex(n) ** 2
        m = np.eye(2, dtype=complex)
        for ior, d in layers:
            delta = 2 * np.pi / lam * d * q(ior)
            yl = y(ior)
            a = np.array([[np.cos(delta), -1j * np.sin(delta) / yl], [-1j * yl * np.sin(delta), np.cos(delta)]])
            m = m @ a
        y0, ys = y(n0), y(sub)
        B = m[0, 0] + m[0, 1] * ys
        C = m[1, 0] + m[1, 1] * ys
        out.append((y0 * B - C) / (y0 * B + C))
    return out


class StackMueller(unittest.TestCase):
    def test_reflection_entries_are_the_transfer_matrix_amplitudes(self):
        rng = np.random.default_rng(5)
        worst = 0.0
        for i in range(200):
            layers = [(complex(1.1 + 1.5 * rng.random(), 0.0 if rng.random() < 0.5 else 0.3 * rng.random()), 600 * rng.random())
                      for _ in range(1 + i % 3)]
            sub = complex(1.2 + rng.random(), 0) if rng.random() < 0.5 else complex(0.2 + rng.random(), 2 + 3 * rng.random())
            cos_i, n0, lam = 0.05 + 0.95 * rng.random(), 1 + 0.5 * rng.random(), 380 + 400 * rng.random()
            rs, rp = naive_r(lam, cos_i, n0, layers, sub)
            Rs, Rp, x = abs(rs) ** 2, abs(rp) ** 2, rs * np.conj(rp)
            want = np.array([[(Rs + Rp) / 2, (Rs - Rp) / 2, 0, 0], [(Rs - Rp) / 2, (Rs + Rp) / 2, 0, 0],
                             [0, 0, x.real, -x.imag], [0, 0, x.imag, x.real]])
            got = iris.thin_film.stack_mueller(layers, lam, cos_i, n0, sub).R
            self.assertEqual(got.shape, (4, 4))
            worst = max(worst, float(np.abs(got - want).max()))
        self.assertLess(worst, 1e-12)

    def test_unpolarized_response_is_stack_rt(self):
        lam = np.linspace(380.0, 780.0, 7)[:, None]
        cos = np.array([1.0, 0.6, 0.2])[None, :]
        for layers, mode in (([(1.33, 310.0)], "airy"), ([(1.33, 310.0)], "truncated"), ([(1.33, 310.0)], "incoherent"),
                             ([(2.0, 120.0), (1.38 + 0.01j, 95.0)], "transfer_matrix")):
            with self.subTest(mode=mode):
                rt = iris.thin_film.stack_rt(layers, lam, cos, 1.0, "Au" if mode == "transfer_matrix" else 1.5, mode=mode, K=2)
                mu = iris.thin_film.stack_mueller(layers, lam, cos, 1.0, "Au" if mode == "transfer_matrix" else 1.5, mode=mode, K=2)
                self.assertEqual(mu.R.shape, (7, 3, 4, 4))
                unpolarized = np.array([1.0, 0.0, 0.0, 0.0])
                np.testing.assert_allclose(mu.R @ unpolarized, np.stack([rt.R, (rt.Rs - rt.Rp) / 2, 0 * rt.R, 0 * rt.R], -1),
                                           rtol=1e-13, atol=1e-15)
                # The truncated sums' powers are clamped as the materials clamp them, T ≤ 1 − R
                # (spectral/thin_film_polarization.h); stack_rt returns the sums themselves.
                t = np.minimum(rt.T, 1 - np.minimum(rt.R, 1)) if mode == "truncated" else rt.T
                np.testing.assert_allclose(mu.T[..., 0, 0], t, rtol=1e-13, atol=1e-15)

    def test_coherent_stacks_are_pure_and_incoherent_sums_depolarize(self):
        lam, cos = np.linspace(400.0, 700.0, 31), 0.5
        coherent = iris.thin_film.stack_mueller([(1.33, 500.0)], lam, cos, 1.0, 1.5, mode="airy")
        incoherent = iris.thin_film.stack_mueller([(1.33, 500.0)], lam, cos, 1.0, 1.5, mode="incoherent")
        for M, pure in ((coherent.R, True), (coherent.T, True), (incoherent.R, False)):
            ps, pp = M[:, 0, 0] + M[:, 0, 1], M[:, 0, 0] - M[:, 0, 1]
            cross2 = M[:, 2, 2] ** 2 + M[:, 3, 2] ** 2
            if pure:
                np.testing.assert_allclose(cross2, ps * pp, rtol=1e-10)
            else:
                self.assertTrue(np.all(cross2 < ps * pp * (1 - 1e-6)))
            # Physical: unpolarized light stays in the cone S0 ≥ |S1..3|.
            s = M @ np.array([1.0, 0.0, 0.0, 0.0])
            self.assertTrue(np.all(s[:, 0] + 1e-15 >= np.linalg.norm(s[:, 1:], axis=1)))

    def test_no_layers_at_brewster_has_no_p_reflection(self):
        cos_b = np.cos(np.arctan(1.5))  # Brewster's angle of glass from air
        M = iris.thin_film.stack_mueller([], 550.0, cos_b, 1.0, 1.5).R
        self.assertAlmostEqual(float(M[0, 0] - M[0, 1]), 0.0, places=14)  # R_p = 0
        self.assertGreater(float(M[0, 0]), 0.01)

    def test_bad_input_is_rejected_like_stack_rt(self):
        with self.assertRaisesRegex(iris.Error, "thickness -5 nm is negative"):
            iris.thin_film.stack_mueller([(1.33, -5.0)], 550.0, 1.0)
        with self.assertRaisesRegex(iris.Error, "do not broadcast"):
            iris.thin_film.stack_mueller([(1.33, 100.0)], np.ones(3) * 550, np.ones(4))
        with self.assertRaisesRegex(iris.Error, "exactly one layer"):
            iris.thin_film.stack_mueller([(1.33, 100.0), (1.5, 10.0)], 550.0, 1.0, mode="airy")


if __name__ == "__main__":
    unittest.main()
