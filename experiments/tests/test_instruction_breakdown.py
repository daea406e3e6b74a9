"""experiments/perf/instruction_breakdown.py (issue 37, item 1): reading callgrind_annotate's
inclusive listing (a -g build splits a function into one line per source file of inlined code: the
function's own, largest line counts) and the per-sample table built from it."""
import sys
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "perf"))
import instruction_breakdown as ib  # noqa: E402

LOOP = ("iris::Renderer::render(iris::Film&, std::atomic<bool> const*, iris::SpectralFilm*, iris::StokesFilm*) "
        "const::{lambda(tbb::detail::d1::blocked_range<int> const&)#2}::operator()(tbb::detail::d1::blocked_range<int> const&) const")

# Trimmed from a real listing (callgrind 3.19) of the spheres scene, with a -g build's split lines.
LISTING = f"""--------------------------------------------------------------------------------
Ir
--------------------------------------------------------------------------------
3,798,268,071 (100.0%)  PROGRAM TOTALS

--------------------------------------------------------------------------------
Ir                      file:function
--------------------------------------------------------------------------------
3,607,686,257 (94.98%)  /work/main/render/renderer.cpp:{LOOP} [/tmp/build-g/render]
2,982,838,930 (78.53%)  /work/main/integrators/path.cpp:iris::PathIntegrator::Li(iris::Scene const&, iris::Ray const&) const [/tmp/build-g/render]
1,117,042,037 (29.41%)  /work/main/render/scene.cpp:iris::Scene::intersect(iris::Ray const&) const [/tmp/build-g/render]
  423,651,534 (11.15%)  ???:rtcIntersect1 [/usr/lib/x86_64-linux-gnu/libembree3.so.3.13.5]
  136,286,342 ( 3.59%)  /usr/include/glm/detail/type_vec3.inl:iris::Scene::intersect(iris::Ray const&) const
   30,631,564 ( 0.81%)  /work/main/core/sphere_intersection.h:iris::Scene::intersect(iris::Ray const&) const
"""


class ParseInclusive(unittest.TestCase):
    def test_total_and_largest_line_per_function(self):
        total, costs = ib.parse_inclusive(LISTING)
        self.assertEqual(total, 3_798_268_071)
        self.assertEqual(costs["iris::Scene::intersect(iris::Ray const&) const"], 1_117_042_037)
        self.assertEqual(costs["rtcIntersect1"], 423_651_534)
        self.assertEqual(ib.cost_of(costs, "iris::PathIntegrator::Li("), 2_982_838_930)
        self.assertIsNone(ib.cost_of(costs, "iris::toXYZ("))

    def test_breakdown_per_camera_sample(self):
        total, costs = ib.parse_inclusive(LISTING)
        rows, loop = ib.breakdown(ib.IRIS_ROWS, total, costs, samples=614_400)
        self.assertEqual(loop, 3_607_686_257)
        by = {r["what"].strip(): r for r in rows}
        self.assertEqual(by["render loop (tiles, samples, film)"]["per sample"], "5,872")
        self.assertEqual(by["of which ray queries (`Scene::intersect`)"]["share of loop"], "31.0 %")
        self.assertEqual(by["spectrum to XYZ (`toXYZ`)"]["per sample"], "—")  # absent from the listing
        outside = rows[-1]
        self.assertEqual(outside["instructions"], 3_798_268_071 - 3_607_686_257)

    def test_a_listing_without_the_render_loop_is_refused(self):
        total, costs = ib.parse_inclusive(LISTING.replace(LOOP, "iris::somethingElse()"))
        with self.assertRaises(SystemExit) as e:
            ib.breakdown(ib.IRIS_ROWS, total, costs, samples=1)
        self.assertIn("no render-loop function", str(e.exception))

    def test_whole_process_estimate_scales_only_the_loop(self):
        run = {"loop": 800, "total": 1000}
        self.assertEqual(ib.at64(run, 8), 800 * 8 + 200)


if __name__ == "__main__":
    unittest.main()
