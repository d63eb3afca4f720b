"""The stress prediction metrics of the GRIP paper (Section V-D), per grasp, and their means
over the test grasps of each category. x is the prediction, y the simulated stress, both per
object point (Pa); numpy arrays or anything np.asarray takes (CPU tensors).

relative MAE = mean_i |x_i - y_i| / max_i |y_i|
  The paper writes the sum over i of |x_i - y_i| over max_i |y_i| and calls it a mean absolute
  error of 7-9 %. The sum over thousands of points would be far above 100 % for any
  prediction of that quality; only the mean gives such values, so we take the mean.

KL = sum_i yhat_i log(yhat_i / xhat_i), with xhat, yhat the stresses normalized to sum 1
  A predicted 0 where the simulation has stress would make it infinite, and a field of all
  zeros has no distribution, so both are taken as (x_i + eps) / sum_j (x_j + eps) with
  eps = EPSILON times the mean of |y| (1e-12 Pa if y is all zero): far below any stress that
  matters, and scale-free, as the metric is. Negative predictions are clipped to 0 first.
"""
import numpy as np

EPSILON = 1e-9


def relative_mae(x, y):
    """mean |x - y| / max |y|; NaN where y is all zero (no scale to be relative to)."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    scale = np.abs(y).max()
    return float(np.abs(x - y).mean() / scale) if scale > 0 else float("nan")


def kl_divergence(x, y):
    """KL(yhat || xhat) of the stresses normalized to sum 1, zeros guarded (module doc)."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    eps = EPSILON * np.abs(y).mean() if np.abs(y).max() > 0 else 1e-12
    xhat = np.clip(x, 0, None) + eps
    yhat = np.clip(y, 0, None) + eps
    xhat, yhat = xhat / xhat.sum(), yhat / yhat.sum()
    return float((yhat * np.log(yhat / xhat)).sum())


def grasp_metrics(x, y):
    return {"relative_mae": relative_mae(x, y), "kl": kl_divergence(x, y)}


def by_category(results):
    """results: [(category, {metric: value})] per test grasp -> {category: {"grasps": n,
    metric: mean over the grasps where it is defined}}."""
    table = {}
    for category, values in results:
        table.setdefault(category, []).append(values)
    summary = {}
    for category, rows in sorted(table.items()):
        summary[category] = {"grasps": len(rows)}
        for name in rows[0]:
            defined = [r[name] for r in rows if np.isfinite(r[name])]
            summary[category][name] = float(np.mean(defined)) if defined else float("nan")
    return summary
