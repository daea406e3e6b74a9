"""iris.Material: every registered BSDF can be created from a dict or XML; eval equals the C++
BSDF::eval exactly (spectral and RGB mode); sample/pdf/eval agree; energy conservation can be
checked from Python; bad input raises iris.Error with the fragment's line."""
import tempfile
import unittest
from pathlib import Path

from support import iris, np, num, reference

GOLD = {"type": "roughconductor", "material": "Au", "alpha": 0.3, "distribution": "ggx"}


def hemisphere(n, seed=0):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05
    return (v / np.linalg.norm(v, axis=1, keepdims=True)).astype(np.float32)


class MaterialValues(unittest.TestCase):
    def eval_against_cxx(self, spec, wavelengths):
        m = iris.Material(spec)
        wo, wi = hemisphere(6, 1), hemisphere(6, 2)
        f = m.eval(wo, wi, wavelengths_nm=wavelengths)
        with tempfile.TemporaryDirectory() as tmp:
            xml = Path(tmp) / "m.xml"
            xml.write_text(m.xml)
            lam = [] if wavelengths is None else list(np.float32(wavelengths))
            queries = [" ".join(["bsdf", str(xml), str(len(lam))] + [num(l) for l in lam] +
                                [num(x) for x in wo[i]] + [num(x) for x in wi[i]]) for i in range(len(wo))]
            ref = np.array(reference(queries), dtype=np.float32)
        np.testing.assert_array_equal(f, ref)
        self.assertGreater(float(f.max()), 0.0)
        return f

    def test_spectral_eval_equals_cxx(self):
        self.eval_against_cxx(GOLD, [450.0, 550.0, 650.0, 700.0])

    def test_rgb_eval_equals_cxx(self):
        self.eval_against_cxx(GOLD, None)

    def test_thin_film_eval_equals_cxx(self):
        self.eval_against_cxx({"type": "thinfilm", "thickness": 320.0, "film_ior": 1.45, "alpha": 0.2}, [420.0, 555.5])

    def test_dict_and_xml_give_the_same_bsdf(self):
        xml = ('<bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.3"/>'
               '<string name="distribution" value="ggx"/></bsdf>')
        wo, wi = hemisphere(4, 3), hemisphere(4, 4)
        np.testing.assert_array_equal(iris.Material(xml).eval(wo, wi), iris.Material(GOLD).eval(wo, wi))

    def test_broadcasting_and_shapes(self):
        m = iris.Material({"type": "diffuse", "reflectance": 0.5})
        wo = np.array([0.0, 0.0, 1.0])
        wi = hemisphere(10).reshape(2, 5, 3)
        f = m.eval(wo, wi, wavelengths_nm=np.linspace(400, 700, 40))  # more than 32 wavelengths
        self.assertEqual(f.shape, (2, 5, 40))
        np.testing.assert_allclose(f, 0.5 / np.pi, rtol=1e-6)  # Lambert: ρ/π
        self.assertEqual(m.pdf(wo, wi).shape, (2, 5))

    def test_sample_agrees_with_eval_and_pdf(self):
        m = iris.Material(GOLD)
        n = 64
        rng = np.random.default_rng(5)
        wo = np.tile(np.float32([0.3, 0.0, 0.954]), (n, 1))
        s = m.sample(wo, rng.random(n), rng.random((n, 2)), wavelengths_nm=[550.0])
        ok = s["valid"]
        self.assertGreater(int(ok.sum()), n // 2)
        np.testing.assert_allclose(s["pdf"][ok], m.pdf(wo[ok], s["wi"][ok], wavelengths_nm=[550.0]), rtol=1e-4)
        np.testing.assert_allclose(s["f"][ok], m.eval(wo[ok], s["wi"][ok], wavelengths_nm=[550.0]), rtol=1e-4)
        self.assertTrue(np.all(s["flags"][ok] & iris.materials.GLOSSY))

    def test_energy_conservation_of_a_conductor(self):
        # Directional albedo ∫ f cosθi dωi by BSDF sampling: at most 1 (single scattering loses energy).
        m = iris.Material({"type": "roughconductor", "material": "none", "alpha": 0.5})
        n = 20000
        rng = np.random.default_rng(7)
        wo = np.tile(np.float32([0.0, 0.0, 1.0]), (n, 1))
        s = m.sample(wo, rng.random(n), rng.random((n, 2)))
        w = np.where(s["valid"][:, None], s["f"] * np.abs(s["wi"][:, 2:3]) / np.maximum(s["pdf"][:, None], 1e-30), 0.0)
        mean, err = w.mean(axis=0), w.std(axis=0) / np.sqrt(n)
        self.assertTrue(np.all(mean <= 1.0 + 4 * err), mean)
        self.assertTrue(np.all(mean > 0.8), mean)

    def test_every_registered_material_can_be_created(self):
        types = iris.materials.material_types()
        self.assertIn("diffuse", types)
        self.assertIn("thinfilm", types)
        created = 0
        for t in types:
            try:
                iris.Material({"type": t})
                created += 1
            except iris.Error:
                pass  # some need a parameter (e.g. a nested BSDF)
        self.assertGreater(created, len(types) // 2)


class MaterialErrors(unittest.TestCase):
    def test_unknown_plugin_name(self):
        with self.assertRaisesRegex(iris.Error, r"<string>:1: .*bsdf type 'nosuch'.*supported: .*diffuse"):
            iris.Material({"type": "nosuch"})

    def test_unknown_parameter_names_the_line(self):
        with self.assertRaisesRegex(iris.Error, r"<string>:2: .*colour"):
            iris.Material('<bsdf type="diffuse">\n<float name="colour" value="1"/></bsdf>')

    def test_bad_directions_and_wavelengths(self):
        m = iris.Material({"type": "diffuse"})
        with self.assertRaisesRegex(iris.Error, "3-vectors"):
            m.eval(np.ones((4, 2)), np.ones((4, 2)))
        with self.assertRaisesRegex(iris.Error, "not a direction"):
            m.eval([0, 0, 0], [0, 0, 1])
        with self.assertRaisesRegex(iris.Error, "nan"):
            m.eval([0, 0, np.nan], [0, 0, 1])
        with self.assertRaisesRegex(iris.Error, "outside"):
            m.eval([0, 0, 1], [0, 0, 1], wavelengths_nm=[1000.0])
        with self.assertRaisesRegex(iris.Error, r"\[0, 1\)"):
            m.sample([0, 0, 1], 1.5, [0.5, 0.5])


if __name__ == "__main__":
    unittest.main()
