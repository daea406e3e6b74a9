"""iris.thin_film: film-stack reflectance and transmittance equal the C++ functions' values exactly,
for every mode, complex and measured indices, broadcasting; bad input raises."""
import unittest

from support import iris, np, num, reference


def film_query(mode, K, lam, cos, n0, sub, layers):
    parts = ["film", mode, str(K), num(lam), num(cos), num(n0), num(sub.real), num(sub.imag), str(len(layers))]
    for ior, d in layers:
        parts += [num(ior.real), num(ior.imag), num(d)]
    return " ".join(parts)


class StackRT(unittest.TestCase):
    lam = np.linspace(380.0, 780.0, 9)
    cos = np.array([1.0, 0.7, 0.3, 0.05])

    def check_against_cxx(self, layers, mode, K=1, substrate=1.5 + 0.0j, n0=1.0):
        r = iris.thin_film.stack_rt(layers, self.lam[:, None], self.cos[None, :], n0, substrate, mode=mode, K=K)
        self.assertEqual(r.Rs.shape, (self.lam.size, self.cos.size))
        queries = [film_query(mode, K, l, c, n0, complex(substrate), [(complex(i), d) for i, d in layers])
                   for l in self.lam for c in self.cos]
        ref = np.array(reference(queries)).reshape(self.lam.size, self.cos.size, 4)
        for k, name in enumerate("Rs Rp Ts Tp".split()):
            np.testing.assert_array_equal(getattr(r, name), ref[..., k], err_msg=f"{mode} {name}")
        return r

    def test_transfer_matrix_two_layers_equals_cxx(self):
        r = self.check_against_cxx([(2.0 + 0.0j, 120.0), (1.38 + 0.0j, 95.0)], "transfer_matrix")
        np.testing.assert_allclose(r.R + r.T, 1.0, atol=1e-12)  # lossless stack

    def test_single_film_modes_equal_cxx(self):
        for mode, K in (("airy", 1), ("truncated", 1), ("truncated", 3), ("incoherent", 1)):
            with self.subTest(mode=mode, K=K):
                self.check_against_cxx([(1.33 + 0.0j, 300.0)], mode, K)

    def test_complex_indices_equal_cxx(self):
        self.check_against_cxx([(1.8 + 0.05j, 80.0)], "transfer_matrix", substrate=0.2 + 3.1j)

    def test_measured_conductor_by_name(self):
        names = iris.thin_film.conductor_names()
        self.assertIn("Au", names)
        gold = iris.thin_film.ior("Au", self.lam)
        ref = reference([f"ior Au {num(l)}" for l in self.lam])
        np.testing.assert_array_equal(gold.real, [x[0] for x in ref])
        np.testing.assert_array_equal(gold.imag, [x[1] for x in ref])
        r = iris.thin_film.stack_rt([(1.45, 250.0)], self.lam, 1.0, 1.0, "Au")
        ref = reference([film_query("transfer_matrix", 1, l, 1.0, 1.0, g, [(1.45 + 0j, 250.0)]) for l, g in zip(self.lam, gold)])
        np.testing.assert_array_equal(r.Rs, [x[0] for x in ref])
        self.assertTrue(np.all(r.T >= 0))

    def test_dielectric_preset_by_name(self):
        np.testing.assert_array_equal(iris.thin_film.ior("water", [400.0, 700.0]).real, np.float32(1.333))

    def test_no_layers_is_fresnel_and_normal_incidence_formula(self):
        r = iris.thin_film.stack_rt([], 550.0, 1.0, 1.0, 1.5)
        self.assertAlmostEqual(float(r.R), ((1.5 - 1) / (1.5 + 1)) ** 2, places=15)  # Fresnel at normal incidence

    def test_belcour_barla_equals_cxx(self):
        d = np.array([0.0, 150.0, 400.0])
        rgb = iris.thin_film.belcour_barla_rgb(1.33, d, 0.8, 1.0, 1.5)
        self.assertEqual(rgb.shape, (3, 3))
        ref = reference([f"bb {c} 0.8 1.0 1.33 {num(x)} 1.5 0.0" for x in d for c in range(3)])
        np.testing.assert_array_equal(rgb.ravel(), [x[0] for x in ref])

    def test_negative_thickness_is_rejected(self):
        with self.assertRaisesRegex(iris.Error, "thickness -5 nm is negative"):
            iris.thin_film.stack_rt([(1.33, -5.0)], 550.0, 1.0)

    def test_nan_is_rejected(self):
        with self.assertRaisesRegex(iris.Error, "cos_theta: entry 1 is nan"):
            iris.thin_film.stack_rt([(1.33, 100.0)], 550.0, [1.0, np.nan])

    def test_wrong_dtype_and_shapes_are_rejected(self):
        with self.assertRaises(TypeError):
            iris.thin_film.stack_rt([(1.33, 100.0)], ["550"], 1.0)
        with self.assertRaisesRegex(iris.Error, "do not broadcast"):
            iris.thin_film.stack_rt([(1.33, 100.0)], np.ones(3) * 550, np.ones(4))
        with self.assertRaisesRegex(iris.Error, "exactly one layer"):
            iris.thin_film.stack_rt([(1.33, 100.0), (1.5, 10.0)], 550.0, 1.0, mode="airy")

    def test_unknown_ior_name_is_rejected(self):
        with self.assertRaisesRegex(iris.Error, "unknown index of refraction 'unobtainium'"):
            iris.thin_film.stack_rt([("unobtainium", 100.0)], 550.0, 1.0)

    def test_iris_error_is_a_value_error(self):
        self.assertTrue(issubclass(iris.Error, ValueError))


class DeprecatedFilmAlias(unittest.TestCase):
    """iris.film is the thin-film module's old name: it still works for one release, with a warning."""

    def test_alias_forwards_with_a_deprecation_warning(self):
        with self.assertWarns(DeprecationWarning):
            stack_rt = iris.film.stack_rt
        self.assertIs(stack_rt, iris.thin_film.stack_rt)

    def test_unknown_names_still_fail(self):
        with self.assertWarns(DeprecationWarning), self.assertRaises(AttributeError):
            iris.film.no_such_function


if __name__ == "__main__":
    unittest.main()
