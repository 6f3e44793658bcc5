"""The third-degree Bezier-type spline of Stelia, Potapenko and Sirenko.

A C1 piecewise cubic that starts and ends at the end points, touches every leg
of the control polygon at a point set by the shape parameter alpha in
[1/3, 2/3], and stays inside the convex hull of the points; every piece is one
cubic Bezier segment. The mathematics is the Rust crate ``bzspline``; this
package converts numpy arrays and releases the GIL while it works.

>>> import numpy as np, bzspline
>>> s = bzspline.Spline(np.arange(1.0, 12.0), [1, 3, 3, 1, 2, 7, 1.5, 1, 10, 2, 1.5])
>>> float(s(2.5))  # the middle of the second leg, (3 + 3) / 2
3.0
"""

from ._core import (
    ALPHA_MAX, ALPHA_MIN, ROBUST_MIN_POINTS, Curve, Spline, __version__, smoothing_curve,
    smoothing_spline,
)
from . import errors, geo

__all__ = [
    "ALPHA_MAX", "ALPHA_MIN", "ROBUST_MIN_POINTS", "Curve", "Spline", "__version__", "errors",
    "geo", "smoothing_curve", "smoothing_spline",
    "to_ppoly", "to_bpoly",
]


def to_ppoly(spline):
    """The spline as scipy's ``PPoly``: the same cubic on every interval.

    Parameters
    ----------
    spline : Spline

    Returns
    -------
    scipy.interpolate.PPoly
        Breakpoints ``spline.x``; coefficients highest power first, in
        ``x - x[i]``. Of a derivative or antiderivative, scipy's own
        derivative or antiderivative of the spline's pieces.
    """
    from scipy.interpolate import PPoly

    c = spline.power_coefficients().T[::-1].copy()
    return _order(PPoly(c, spline.x, extrapolate=spline.extrapolate is not False), spline)


def to_bpoly(spline):
    """The spline as scipy's ``BPoly``: the Bernstein coefficients of every
    piece are the ordinates of its Bezier control points.

    Parameters
    ----------
    spline : Spline

    Returns
    -------
    scipy.interpolate.BPoly
    """
    from scipy.interpolate import BPoly

    c = spline.segments[:, :, 1].T.copy()
    return _order(BPoly(c, spline.x, extrapolate=spline.extrapolate is not False), spline)


def _order(p, spline):
    """``p`` (the pieces of the spline) as the derivative or antiderivative
    ``spline`` evaluates."""
    if spline.nu > 0:
        p = p.derivative(spline.nu)
    elif spline.nu < 0:
        p = p.antiderivative(-spline.nu)
    if spline._offset:
        # PPoly: the constant term; BPoly: every Bernstein coefficient (they
        # sum to one).
        if type(p).__name__ == "PPoly":
            p.c[-1] -= spline._offset
        else:
            p.c -= spline._offset
    return p


Spline.to_ppoly = to_ppoly
Spline.to_bpoly = to_bpoly
