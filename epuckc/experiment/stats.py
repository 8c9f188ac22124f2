"""Mean, standard deviation and the 95% confidence interval of a mean
(Student's t), without anything beyond the standard library."""
from __future__ import annotations

import math

# two-sided 95%: t(0.975, df) for df = 1..30, then a few larger df
_T975 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
         2.201, 2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
         2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]
_T975_LARGE = [(40, 2.021), (60, 2.000), (120, 1.980)]
_Z975 = 1.960


def t975(df: int) -> float:
    """The 97.5% quantile of Student's t with df degrees of freedom (the
    table's values; between its rows, linear in 1/df, which is exact to
    the third decimal)."""
    if df < 1:
        raise ValueError("df >= 1")
    if df <= 30:
        return _T975[df - 1]
    points = [(30, _T975[-1])] + _T975_LARGE + [(math.inf, _Z975)]
    for (d0, t0), (d1, t1) in zip(points, points[1:]):
        if df <= d1:
            x0, x1, x = 1 / d0, (0.0 if d1 == math.inf else 1 / d1), 1 / df
            return t1 + (t0 - t1) * (x - x1) / (x0 - x1)
    return _Z975


def describe(values: list) -> dict:
    """n, mean, sd and the 95% interval of the mean (sd and the interval
    empty for fewer than 2 values)."""
    n = len(values)
    if n == 0:
        return {"n": 0, "mean": None, "sd": None, "ci_low": None, "ci_high": None}
    mean = math.fsum(values) / n
    if n < 2:
        return {"n": 1, "mean": mean, "sd": None, "ci_low": None, "ci_high": None}
    sd = math.sqrt(math.fsum((v - mean) ** 2 for v in values) / (n - 1))
    half = t975(n - 1) * sd / math.sqrt(n)
    return {"n": n, "mean": mean, "sd": sd, "ci_low": mean - half, "ci_high": mean + half}
