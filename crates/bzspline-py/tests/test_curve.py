"""Curves in the plane and in space."""

import pickle

import numpy as np
import pytest

import bzspline

SQUARE = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def test_closed_square_pulls_knots_a_tenth_inside():
    c = bzspline.Curve(SQUARE, closed=True, param="uniform")
    k = c.knot_points
    assert np.allclose(k[0], [0.1, 0.1]) and np.allclose(k[2], [0.9, 0.9])
    assert c.arclen() < 4.0
    assert c.svg_path().endswith("Z")
    assert c.segments.shape == (4, 4, 2)
    lo, hi = c.bbox()
    assert np.all(lo >= -1e-12) and np.all(hi <= 1 + 1e-12)


def test_evaluation_shapes_and_derivatives():
    rng = np.random.default_rng(1)
    pts = rng.normal(size=(30, 3))
    c = bzspline.Curve(pts, param="chordal")
    t = np.linspace(*c.knots[[0, -1]], 12).reshape(3, 4)
    assert c(t).shape == (3, 4, 3) and c(t, nu=1).shape == (3, 4, 3)
    assert np.allclose(c(c.knots[0]), pts[0]) and np.allclose(c(c.knots[-1]), pts[-1])
    assert c.curvature(t).shape == (3, 4)


def test_resample_nearest_and_flatten():
    th = np.linspace(0, np.pi, 40)
    c = bzspline.Curve(np.column_stack([np.cos(th), np.sin(th)]))
    r = c.resample(n=9)
    assert r.shape == (9, 2)
    steps = np.linalg.norm(np.diff(r, axis=0), axis=1)
    assert steps.max() - steps.min() < 1e-3
    s = c.resample(step=0.5)
    assert len(s) == int(c.arclen() / 0.5) + 1 + 1 or len(s) == int(c.arclen() / 0.5) + 1
    t, p, d = c.nearest([0.0, 2.0])
    assert np.isclose(d, np.linalg.norm(p - [0.0, 2.0])) and 0.98 < p[1] <= 1.0
    f = c.flatten(1e-4)
    assert np.allclose(f[0], [1.0, 0.0]) and np.allclose(f[-1], [-1.0, 0.0], atol=1e-12)
    with pytest.raises(ValueError):
        c.resample()


def test_curves_pickle():
    for c in [
        bzspline.Curve(SQUARE, closed=True),
        bzspline.Curve(SQUARE, param=[0.0, 1.0, 3.0, 4.0], alpha=[0.4, 0.5, 0.6]),
        bzspline.Curve(SQUARE, through=True),
    ]:
        back = pickle.loads(pickle.dumps(c))
        t = np.linspace(*c.knots[[0, -1]], 25)
        assert np.array_equal(back(t), c(t))


def test_bad_curves_raise():
    with pytest.raises(ValueError, match=r"points\[1\]"):
        bzspline.Curve([[0.0, 0.0], [np.inf, 1.0], [2.0, 0.0]])
    with pytest.raises(ValueError):
        bzspline.Curve([0.0, 1.0, 2.0])
    with pytest.raises(ValueError):
        bzspline.Curve(SQUARE, param="spiral")
    with pytest.raises(ValueError):
        bzspline.Curve(SQUARE)(100.0)
