"""glTF from Python: iris.load_file reads .gltf/.glb and renders in both modes; the glTF material's
thin-film readings are selectable by rgb_mode; iris.thin_film.khr_iridescence_rgb and gulbrandsen_ior
behave as their formulas say; bad input raises iris.Error naming it."""
import unittest

from support import REPO, iris, np

ASSETS = REPO / "tests" / "data" / "gltf"


class LoadAndRender(unittest.TestCase):
    def test_gltf_and_glb_render_in_both_modes(self):
        for name in ("basic.gltf", "basic.glb"):
            scene = iris.load_file(str(ASSETS / name), res=24, spp=2)
            for mode in ("spectral", "rgb"):
                r = iris.render(scene, spp=2, mode=mode, seed=1)
                self.assertEqual(r.image.shape[1], 24)
                self.assertTrue(np.isfinite(r.image).all())
                self.assertGreater(float(r.image.mean()), 0.01, f"{name} {mode}")

    def test_errors_name_the_file_and_json_path(self):
        with self.assertRaises(iris.Error) as e:
            iris.load_file(str(ASSETS / "bad_accessor_range.gltf"))
        self.assertIn("bad_accessor_range.gltf", str(e.exception))
        self.assertIn("/accessors/0", str(e.exception))


class ThinFilmReadings(unittest.TestCase):
    base = {"type": "gltf_pbr", "base_color": [0.95, 0.64, 0.54], "metallic": 1.0, "roughness": 0.4,
            "iridescence": 1.0, "iridescence_thickness": 400.0, "iridescence_ior": 1.5}

    def test_rgb_mode_switches_the_model(self):
        wo = np.array([[0.3, 0.0, 0.954]])
        wi = np.array([[-0.2, 0.1, 0.975]])
        point = iris.Material(dict(self.base)).eval(wo, wi)
        khr = iris.Material(dict(self.base, rgb_mode="khr_iridescence")).eval(wo, wi)
        self.assertEqual(point.shape, khr.shape)
        self.assertGreater(float(np.abs(point - khr).max()), 1e-3)
        with self.assertRaises(iris.Error):
            iris.Material(dict(self.base, rgb_mode="no_such_model"))

    def test_khr_thick_film_is_the_incoherent_term(self):
        # At 100 µm the harmonics vanish: F = R12 + T121² R23 / (1 − R12 R23) with Schlick terms.
        f0, film, cos1 = 0.04, 1.8, 0.8
        cos2 = np.sqrt(1 - (1 / film) ** 2 * (1 - cos1 ** 2))
        schlick = lambda r0, c: r0 + (1 - r0) * (1 - c) ** 5
        R12 = schlick(((film - 1) / (film + 1)) ** 2, cos1)
        base = (1 + np.sqrt(f0 + 1e-4)) / (1 - np.sqrt(f0 + 1e-4))
        R23 = schlick(((base - film) / (base + film)) ** 2, cos2)
        expected = R12 + (1 - R12) ** 2 * R23 / (1 - R12 * R23)
        F = iris.thin_film.khr_iridescence_rgb(film, 1e5, cos1, f0)
        np.testing.assert_allclose(F, np.full(3, expected), rtol=1e-12)
        self.assertEqual(iris.thin_film.khr_iridescence_rgb(film, [100, 200, 300], cos1, [0.04, 0.5, 0.9]).shape, (3, 3))
        with self.assertRaises(iris.Error):
            iris.thin_film.khr_iridescence_rgb(film, -1.0, cos1, f0)

    def test_gulbrandsen_keeps_the_normal_reflectivity(self):
        r = np.array([0.1, 0.5, 0.9])
        n = iris.thin_film.gulbrandsen_ior(r, 0.5)
        R = np.abs((n - 1) / (n + 1)) ** 2
        np.testing.assert_allclose(R, r, rtol=1e-12)
        with self.assertRaises(iris.Error):
            iris.thin_film.gulbrandsen_ior(1.5, 0.5)


if __name__ == "__main__":
    unittest.main()
