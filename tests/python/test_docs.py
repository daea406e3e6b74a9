"""Every ```python example of docs/python.md runs (in order, in one namespace per section,
from the repository root) without raising."""
import os
import re
import unittest

from support import REPO

DOC = REPO / "docs" / "python.md"
BLOCK = re.compile(r"^```python\n(.*?)^```", re.M | re.S)


class DocExamples(unittest.TestCase):
    def test_every_example_runs(self):
        text = DOC.read_text(encoding="utf-8")
        blocks = BLOCK.findall(text)
        self.assertGreaterEqual(len(blocks), 4)
        cwd = os.getcwd()
        os.chdir(REPO)
        try:
            for i, code in enumerate(blocks):
                with self.subTest(example=i + 1, first_line=code.splitlines()[0]):
                    exec(compile(code, f"{DOC}:example {i + 1}", "exec"), {"__name__": f"doc_example_{i}"})
        finally:
            os.chdir(cwd)

    def test_a_failing_example_is_reported(self):
        with self.assertRaises(ZeroDivisionError):
            exec(compile("1 / 0", "example", "exec"), {})


if __name__ == "__main__":
    unittest.main()
