#!/usr/bin/python3
"""examples/stress_prediction/metrics.py on inputs whose values are worked out by hand here.

  test_stress_metrics.py SOURCE_DIR

The metrics need numpy only, not torch. Exit 77 (skipped) when Debian's Python lacks numpy,
except under CI (the CI variable set), where scripts/install-deps.sh has installed it.
"""
import math
import os
import sys


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def close(name, got, expected, tolerance=1e-7):
    if not abs(got - expected) <= tolerance * max(1.0, abs(expected)):
        fail(f"{name} = {got!r}, expected {expected!r}")
    print(f"{name} = {got:.9f} (expected {expected:.9f})")


def main():
    try:
        import numpy as np
    except ImportError as error:
        if os.environ.get("CI"):
            fail(f"{error}; scripts/install-deps.sh installs python3-numpy")
        print(f"skipped: {error}")
        return 77
    sys.dont_write_bytecode = True
    sys.path.insert(0, os.path.join(sys.argv[1], "examples", "stress_prediction"))
    import metrics

    x, y = [1.0, 2.0, 3.0], [1.0, 1.0, 4.0]
    # |x - y| = 0, 1, 1: mean 2/3, over max |y| = 4.
    close("relative MAE", metrics.relative_mae(x, y), (0 + 1 + 1) / 3 / 4)
    # xhat = 1/6, 2/6, 3/6; yhat = 1/6, 1/6, 4/6.
    kl = 1 / 6 * math.log(1.0) + 1 / 6 * math.log(0.5) + 4 / 6 * math.log((4 / 6) / (3 / 6))
    close("KL", metrics.kl_divergence(x, y), kl)
    close("KL of a field and itself", metrics.kl_divergence(y, y), 0.0)
    # Scale-free: both metrics compare shapes, so 1000 x both gives the same values.
    close("relative MAE x1000", metrics.relative_mae(np.array(x) * 1e3, np.array(y) * 1e3),
          2 / 3 / 4)
    close("KL x1000", metrics.kl_divergence(np.array(x) * 1e3, np.array(y) * 1e3), kl)
    # A prediction of zeros where y = [0, 0, 2]: yhat = (0, 0, 1) up to eps, xhat uniform, so
    # KL = log 3 (the eps guard keeps it finite); relative MAE = (2 / 3) / 2.
    close("KL of a zero prediction", metrics.kl_divergence([0, 0, 0], [0, 0, 2]), math.log(3),
          1e-6)
    close("relative MAE of a zero prediction", metrics.relative_mae([0, 0, 0], [0, 0, 2]), 1 / 3)
    if not math.isnan(metrics.relative_mae([1, 2], [0, 0])):
        fail("relative MAE against an all-zero field should be NaN (no scale)")

    summary = metrics.by_category([("bowl", {"relative_mae": 0.1, "kl": 0.2}),
                                   ("bowl", {"relative_mae": 0.3, "kl": float("nan")}),
                                   ("mug", {"relative_mae": 0.5, "kl": 0.4})])
    expected = {"bowl": {"grasps": 2, "relative_mae": 0.2, "kl": 0.2},
                "mug": {"grasps": 1, "relative_mae": 0.5, "kl": 0.4}}
    if summary.keys() != expected.keys() or any(
            abs(summary[c][k] - v) > 1e-12 for c in expected for k, v in expected[c].items()):
        fail(f"by_category gave {summary}, expected {expected}")
    print("by_category: means per category, NaN left out")
    return 0


if __name__ == "__main__":
    sys.exit(main())
