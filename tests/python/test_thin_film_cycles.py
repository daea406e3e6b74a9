"""Blender Cycles 4.2's thin film (iris.thin_film.cycles_4_2_rgb, spectral/thin_film_cycles.h)
against an independent NumPy re-derivation of the published method (Blender commit 17f2cdd1,
intern/cycles/kernel/closure/bsdf_util.h fresnel_iridescence; the Gaussian fit of Belcour &
Barla 2017; shader.cpp's XYZ → Rec.709 matrix and white), its limits, and its input checks;
and the thinfilm material's rgb_mode "cycles_4_2"."""
import unittest

from support import iris, np

XYZ_TO_REC709 = np.array([[3.2404542, -1.5371385, -0.4985314],
                          [-0.9692660, 1.8760108, 0.0415560],
                          [0.0556434, -0.2040259, 1.0572252]])


def polarized_fresnel(cos_i, eta):
    """(R_s, R_p), phases (0 or π where the amplitude is negative), |cos θt|; None on TIR."""
    sin2_t = (1.0 - cos_i ** 2) / eta ** 2
    if sin2_t >= 1.0:
        return None
    cos_t = np.sqrt(1.0 - sin2_t)
    r = np.array([(cos_i - eta * cos_t) / (cos_i + eta * cos_t), (eta * cos_i - cos_t) / (eta * cos_i + cos_t)])
    return r ** 2, np.where(r < 0, np.pi, 0.0), cos_t


def sensitivity_xyz(opd_nm, shift):
    phase = 2 * np.pi * opd_nm * 1e-9
    val, pos, var = (np.array([5.4856e-13, 4.4201e-13, 5.2481e-13]), np.array([1.6810e6, 1.7953e6, 2.2084e6]),
                     np.array([4.3278e9, 9.3046e9, 6.6121e9]))
    xyz = val * np.sqrt(2 * np.pi * var) * np.cos(pos * phase + shift) * np.exp(-phase ** 2 * var)
    xyz[0] += 1.64408e-8 * np.cos(2.2399e6 * phase + shift) * np.exp(-4.5282e9 * phase ** 2)
    return xyz / 1.0685e-7


def cycles_reference(n1, n2, n3, cos1, d):
    if d <= 0.1:
        top = polarized_fresnel(cos1, n3 / n1)
        return np.full(3, top[0].mean())
    if d < 30:
        t = d / 30
        n2 = n1 + (n2 - n1) * t * t * (3 - 2 * t)
    top = polarized_fresnel(cos1, n2 / n1)
    if top is None:
        return np.ones(3)
    R12, phi12, cos2 = top
    bottom = polarized_fresnel(cos2, n3 / n2)
    if bottom is None:
        return np.ones(3)
    R23, phi23, _ = bottom
    opd = 2 * n2 * d * cos2
    xyz = np.zeros(3)
    for pol in range(2):
        T = 1 - R12[pol]
        Rs = T * T * R23[pol] / (1 - R12[pol] * R23[pol])
        R = np.full(3, R12[pol] + Rs)
        for m in (1, 2, 3):
            R += 2 * (Rs - T) * np.sqrt(R12[pol] * R23[pol]) ** m * sensitivity_xyz(m * opd, m * (np.pi - phi12[pol] + phi23[pol]))
        xyz += 0.5 * R
    white = np.linalg.solve(XYZ_TO_REC709, np.ones(3))
    return np.clip(XYZ_TO_REC709 @ (xyz * white), 0, 1)


class CyclesThinFilm(unittest.TestCase):
    def test_matches_an_independent_derivation(self):
        rng = np.random.default_rng(7)
        for _ in range(200):
            n2, n3, cos1 = rng.uniform(1.2, 2.4), rng.uniform(1.3, 2.0), rng.uniform(0.02, 1.0)
            d = rng.choice([rng.uniform(0, 0.1), rng.uniform(0.1, 30), rng.uniform(30, 1500)])
            got = iris.thin_film.cycles_4_2_rgb(n2, d, cos1, n3)
            np.testing.assert_allclose(got, cycles_reference(1.0, n2, n3, cos1, d), atol=1e-10,
                                       err_msg=f"film {n2} base {n3} cos {cos1} d {d}")

    def test_broadcasts_and_limits(self):
        d = np.array([0.0, 200.0, 600.0])
        cos = np.array([1.0, 0.5])
        out = iris.thin_film.cycles_4_2_rgb(1.4, d[:, None], cos[None, :], 1.5)
        self.assertEqual(out.shape, (3, 2, 3))
        # d = 0: the bare base, the exact film of zero thickness.
        bare = iris.thin_film.stack_rt([(1.4, 0.0)], 550.0, cos, 1.0, 1.5, mode="airy").R
        np.testing.assert_allclose(out[0], np.repeat(bare[:, None], 3, axis=1), atol=1e-12)
        self.assertGreater(np.ptp(out[1, 0]), 0.01, "a 200 nm film is coloured")

    def test_bad_input_is_rejected(self):
        with self.assertRaises(iris.Error):
            iris.thin_film.cycles_4_2_rgb(1.4, -10.0, 0.5)
        with self.assertRaises(iris.Error):
            iris.thin_film.cycles_4_2_rgb(1.4, 100.0, 1.5)
        with self.assertRaises(iris.Error):
            iris.thin_film.cycles_4_2_rgb(1.4, [100.0, 200.0], [0.5, 0.6, 0.7])


class CyclesMaterial(unittest.TestCase):
    film = {"type": "thinfilm", "substrate": "dielectric", "substrate_eta": 1.5, "thickness": 450.0, "film_ior": 1.33,
            "alpha": 0.2, "rgb_mode": "cycles_4_2"}

    def test_rgb_mode_cycles_4_2_changes_the_rgb_reading_only(self):
        wo = np.array([[0.3, 0.0, 0.954]])
        wi = np.array([[-0.2, 0.1, 0.975]])
        point = iris.Material(dict(self.film, rgb_mode="point")).eval(wo, wi)
        cycles = iris.Material(dict(self.film)).eval(wo, wi)
        self.assertGreater(float(np.abs(point - cycles).max()), 1e-3)
        lam = np.array([450.0, 550.0, 650.0])
        np.testing.assert_allclose(iris.Material(dict(self.film)).eval(wo, wi, wavelengths_nm=lam),
                                   iris.Material(dict(self.film, rgb_mode="point")).eval(wo, wi, wavelengths_nm=lam), rtol=1e-6)

    def test_a_metal_substrate_is_rejected(self):
        with self.assertRaises(iris.Error):
            iris.Material(dict(self.film, substrate="conductor"))


if __name__ == "__main__":
    unittest.main()
