"""experiments/perf/run.py: the wait for an idle machine before measuring (a run started right after
other work used to sample that work's decaying load average and call its own timings loaded)."""
import sys
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "perf"))
import run  # noqa: E402


class FakeMachine:
    """A 1-minute load average read from a list, one value per poll; sleeping advances a clock."""

    def __init__(self, loads):
        self.loads, self.now, self.polls = list(loads), 0.0, 0

    def getload(self):
        value = self.loads[min(self.polls, len(self.loads) - 1)]
        self.polls += 1
        return (value, 0.0, 0.0)

    def sleep(self, s):
        self.now += s

    def clock(self):
        return self.now


class WaitForIdle(unittest.TestCase):
    def wait(self, loads, limit):
        m = FakeMachine(loads)
        return run.wait_for_idle(limit, threshold=0.375, getload=m.getload, sleep=m.sleep, clock=m.clock, poll_s=10)

    def test_an_idle_machine_is_measured_at_once(self):
        self.assertEqual(self.wait([0.1], limit=300), (0.0, 0.1))

    def test_waits_while_the_load_of_earlier_work_decays(self):
        self.assertEqual(self.wait([1.14, 0.8, 0.5, 0.3, 0.2], limit=300), (30.0, 0.3))

    def test_a_machine_that_stays_busy_is_waited_for_only_until_the_limit(self):
        waited, load = self.wait([1.5], limit=60)
        self.assertEqual(waited, 60.0)
        self.assertGreater(load, run.FOREIGN_LOAD_LIMIT)  # and the report will say it was loaded

    def test_no_wait_when_the_limit_is_zero(self):
        self.assertEqual(self.wait([2.0], limit=0), (0.0, 2.0))


if __name__ == "__main__":
    unittest.main()
