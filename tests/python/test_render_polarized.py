"""iris.render(mode="polarized"): the image is S0 and Mitsuba 3's stokes integrator returns S0..S3 as
`stokes` (4, H, W, 3). Ideal polarizers between an area light and the camera (delta paths: exact up
to float rounding) follow Malus's law, I = ½ cos²θ, with fully polarized light leaving; crossed
polarizers transmit nothing; other integrators return no Stokes channels; unknown modes raise."""
import unittest

from support import iris, np


def filter_scene(filters, integrator="<integrator type=\"stokes\"><integrator type=\"path\"/></integrator>"):
    """Camera at (0, 10, 0) looking at the light at y = −10 through `filters` (tests/integrators/
    test_polarized_filters.cpp's scene)."""
    return f"""<scene version="2.0.0">
  {integrator}
  <sensor type="perspective"><float name="fov" value="0.5"/>
    <transform name="to_world"><lookat origin="0, 10, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film></sensor>
  <shape type="rectangle">
    <transform name="to_world"><rotate x="1" angle="-90"/><translate y="-10"/></transform>
    <emitter type="area"><spectrum name="radiance" value="1"/></emitter></shape>
  {filters}
</scene>"""


def polarizer(y, angle):
    return (f'<shape type="rectangle"><bsdf type="polarizer"/><transform name="to_world"><rotate x="1" angle="-90"/>'
            f'<rotate y="1" angle="{angle}"/><translate y="{y}"/></transform></shape>')


def stokes_of(xml):
    r = iris.render(iris.load_string(xml), spp=4, seed=3, mode="polarized", colorspace="lin_rec709")
    return r


class PolarizedRender(unittest.TestCase):
    def test_malus_law_and_full_polarization(self):
        open_ = stokes_of(filter_scene(""))
        self.assertEqual(open_.stokes.shape, (4, 1, 1, 3))
        np.testing.assert_allclose(open_.stokes[0], open_.image, rtol=1e-6)   # the image is S0
        np.testing.assert_allclose(open_.stokes[1:], 0.0, atol=1e-6)          # the light is unpolarized
        for angle in (0.0, 30.0, 60.0):
            with self.subTest(angle=angle):
                r = stokes_of(filter_scene(polarizer(-5, 0) + polarizer(0, angle)))
                s = r.stokes[:, 0, 0, 1] / open_.stokes[0, 0, 0, 1]
                self.assertAlmostEqual(s[0], 0.5 * np.cos(np.radians(angle)) ** 2, delta=2e-4)
                self.assertAlmostEqual(np.linalg.norm(s[1:]) / s[0], 1.0, delta=1e-3)

    def test_crossed_polarizers_are_dark(self):
        r = stokes_of(filter_scene(polarizer(-5, 0) + polarizer(0, 90)))
        np.testing.assert_allclose(r.stokes, 0.0, atol=1e-6)

    def test_other_integrators_return_no_stokes_channels(self):
        r = iris.render(iris.load_string(filter_scene(polarizer(0, 0), "<integrator type=\"path\"/>")), spp=4, mode="polarized")
        self.assertIsNone(r.stokes)
        self.assertGreater(float(r.image.sum()), 0.0)
        self.assertIsNone(iris.render(iris.load_string(filter_scene("", "<integrator type=\"path\"/>")), spp=1).stokes)

    def test_unknown_mode_is_rejected(self):
        with self.assertRaisesRegex(iris.Error, "expected spectral, rgb or polarized"):
            iris.render(iris.load_string(filter_scene("")), spp=1, mode="stokes")


if __name__ == "__main__":
    unittest.main()
