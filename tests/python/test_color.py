"""iris.color: CIE tables, spectrum → XYZ equal to the C++ quadrature exactly, OCIO conversions,
RGB upsampling; bad input raises."""
import unittest

from support import iris, np, num, reference


class Spectra(unittest.TestCase):
    def test_cie_tables(self):
        xyz = iris.color.xyz_bar([555.0, 300.0])
        self.assertEqual(xyz.shape, (2, 3))
        self.assertAlmostEqual(float(xyz[0, 1]), 1.0, places=3)  # ȳ peaks at 555 nm
        np.testing.assert_array_equal(xyz[1], 0.0)  # outside the table
        self.assertAlmostEqual(float(iris.color.d65(560.0)), 100.0, places=4)
        self.assertAlmostEqual(iris.color.y_integral(), 106.857, places=2)

    def test_spectrum_to_xyz_equals_cxx(self):
        lam, v = [380.0, 500.0, 620.5, 780.0], [0.1, 0.9, 0.3, 0.05]
        xyz = iris.color.spectrum_to_xyz(lam, v)
        ref = reference(["xyz 4 " + " ".join(f"{num(np.float32(l))} {num(np.float32(x))}" for l, x in zip(lam, v))])[0]
        np.testing.assert_array_equal(xyz, ref)

    def test_constant_spectrum_is_white(self):
        np.testing.assert_allclose(iris.color.spectrum_to_xyz([400, 700], [1, 1]), 1.0, rtol=2e-3)

    def test_conversions(self):
        self.assertIn("CIE-XYZ", iris.color.color_spaces())
        rgb = np.array([[0.2, 0.5, 0.9], [1.0, 1.0, 1.0]], dtype=np.float32)
        back = iris.color.convert(iris.color.convert(rgb, "lin_rec709", "CIE-XYZ"), "CIE-XYZ", "lin_rec709")
        np.testing.assert_allclose(back, rgb, atol=1e-5)
        white = iris.color.convert(np.float32([1, 1, 1]), "lin_rec709", "CIE-XYZ")
        np.testing.assert_allclose(white, [0.9505, 1.0, 1.089], atol=2e-3)  # D65 white
        disp = iris.color.to_display(rgb)
        self.assertEqual(disp.shape, rgb.shape)

    def test_rgb_upsampling_reproduces_the_colour(self):
        s = iris.color.rgb_to_spectrum([0.8, 0.3, 0.1])
        self.assertLess(s.error, 1e-3)
        np.testing.assert_allclose(s.rgb(), [0.8, 0.3, 0.1], atol=1e-3)
        values = s(np.linspace(360, 830, 48))
        self.assertTrue(np.all((values > 0) & (values < 1)))

    def test_bad_input(self):
        with self.assertRaisesRegex(iris.Error, "'nope' is not in"):
            iris.color.convert(np.zeros(3), "nope", "CIE-XYZ")
        with self.assertRaisesRegex(iris.Error, "last dimension is 3"):
            iris.color.convert(np.zeros(4), "lin_rec709", "CIE-XYZ")
        with self.assertRaisesRegex(iris.Error, "strictly increasing|increasing"):
            iris.color.spectrum_to_xyz([500, 400], [1, 1])
        with self.assertRaisesRegex(iris.Error, "nan"):
            iris.color.d65([np.nan])


if __name__ == "__main__":
    unittest.main()
