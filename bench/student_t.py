"""Two-sided 95% quantile of Student's t, shared by the bench scripts.

The same values as shockfit::student_t95 (shockfit/src/group_interval.cpp),
so that an interval recomputed offline from recorded runs is the one the
tools would report: the exact quantiles to three decimals up to 30 degrees
of freedom, beyond that 1.96 + 2.4 / dof (within 0.002 of the quantile).
"""
import math

_TABLE = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
          2.201, 2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
          2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]
NORMAL95 = 1.959963984540054


def t95(dof):
    """Two-sided 95% quantile with `dof` degrees of freedom; inf below 1."""
    if dof < 1:
        return math.inf
    if dof <= len(_TABLE):
        return _TABLE[dof - 1]
    return NORMAL95 + 2.4 / dof
