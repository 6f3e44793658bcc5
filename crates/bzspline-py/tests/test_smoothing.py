"""bzspline.smoothing_spline: the smoothing spline in the method's basis, in
scipy.interpolate.make_smoothing_spline's terms; checked against its exact
limits, against the command, and for accuracy beside scipy's."""

import pickle

import numpy as np
import pytest

import bzspline

from test_defaults import fit


def noisy(n, seed=0, sigma=0.3):
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0, 10, n))
    truth = np.sin(x)
    return x, truth + rng.normal(0, sigma, n), truth


def test_the_result_is_a_spline_with_lam_gcv_and_dof():
    x, y, _ = noisy(300)
    s = bzspline.smoothing_spline(x, y)
    assert isinstance(s, bzspline.Spline)
    assert s.lam > 0 and s.gcv > 0 and 2 < s.dof < 300
    # Given that lam, the same spline.
    t = bzspline.smoothing_spline(x, y, lam=s.lam)
    assert np.array_equal(t.control_values, s.control_values)
    assert t.lam == s.lam
    # The method's spline of its control values.
    u = bzspline.Spline(x, s.control_values)
    assert np.array_equal(u.segments, s.segments)
    assert bzspline.Spline(x, y).lam is None
    r = pickle.loads(pickle.dumps(s))
    assert (r.lam, r.gcv, r.dof) == (s.lam, s.gcv, s.dof)
    assert np.array_equal(r(x), s(x))


def test_lam_zero_passes_through_and_a_huge_lam_is_the_line():
    x, y, _ = noisy(50, seed=1)
    s = bzspline.smoothing_spline(x, y, lam=0.0)
    assert np.allclose(s(x), y, rtol=0, atol=1e-12)
    assert np.allclose(s.control_values, bzspline.Spline(x, y, through=True).control_values,
                       rtol=0, atol=1e-12)
    w = np.random.default_rng(2).uniform(0.5, 2, 50)
    line = bzspline.smoothing_spline(x, y, w, lam=1e14)
    slope, icept = np.polyfit(x, y, 1, w=np.sqrt(w))  # polyfit squares its weights
    assert np.allclose(line(x), icept + slope * x, rtol=0, atol=1e-6)
    assert abs(line.dof - 2) < 1e-6


def test_a_point_of_weight_zero_is_ignored():
    x, y, _ = noisy(80, seed=3)
    w = np.ones(80)
    w[[0, 1, 40, 79]] = 0
    a = bzspline.smoothing_spline(x, y, w)
    y2 = y.copy()
    y2[[0, 1, 40, 79]] += 100
    b = bzspline.smoothing_spline(x, y2, w)
    assert np.array_equal(a.control_values, b.control_values)
    assert a.lam == b.lam


def test_the_same_fit_as_the_command():
    x, y, _ = noisy(120, seed=4)
    table = "x,y\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, y))
    got = fit(["--smooth", "auto"], table)
    s = bzspline.smoothing_spline(x, y)
    assert np.array_equal(s.control_values, np.array(got["values"]))
    assert (s.lam, s.gcv, s.dof) == (got["lambda"], got["gcv"], got["dof"])


def test_bad_input_names_its_place():
    x, y, _ = noisy(10)
    cases = [
        (dict(x=x[:2], y=y[:2]), "at least 3"),
        (dict(x=x[::-1], y=y), "strictly increasing"),
        (dict(x=x, y=y, w=np.r_[1, 1, -1, np.ones(7)]), "weights[2]"),
        (dict(x=x, y=y, w=np.r_[1, 1, 1, np.nan, np.ones(6)]), "weights[3]"),
        (dict(x=x, y=y, w=np.ones(3)), "weights"),
        (dict(x=x, y=y, lam=-1.0), "lambda"),
        (dict(x=x, y=y, lam=float("nan")), "lambda"),
        (dict(x=x, y=y, alpha=0.9), "alphas[0]"),
        (dict(x=x, y=np.r_[y[:5], np.inf, y[6:]]), "values[5]"),
    ]
    for kwargs, want in cases:
        with pytest.raises(ValueError, match=want.replace("[", r"\[").replace("]", r"\]")):
            bzspline.smoothing_spline(**kwargs)


def test_as_close_to_the_truth_as_scipys_fit():
    scipy_interpolate = pytest.importorskip("scipy.interpolate")
    for seed in range(3):
        x, y, truth = noisy(400, seed=seed)
        ours = np.mean((bzspline.smoothing_spline(x, y)(x) - truth) ** 2)
        theirs = np.mean((scipy_interpolate.make_smoothing_spline(x, y)(x) - truth) ** 2)
        assert ours < 1.5 * theirs, (seed, ours, theirs)


def test_a_long_series_lands_closer_to_the_truth_than_the_data():
    x, y, truth = noisy(200_000, seed=5)
    s = bzspline.smoothing_spline(x, y)
    assert np.mean((s(x) - truth) ** 2) < 0.05 * np.mean((y - truth) ** 2)


def test_a_noisy_track_is_smoothed_on_its_times():
    rng = np.random.default_rng(6)
    t = np.linspace(0, 6, 400)
    track = np.c_[10 * np.cos(t), 10 * np.sin(t), t] + rng.normal(0, 0.3, (400, 3))
    c = bzspline.smoothing_curve(track, param=t)
    assert isinstance(c, bzspline.Curve)
    assert np.array_equal(c.knots, t)
    assert c.lam > 0 and 3 < c.dof < 400
    off = lambda p: np.abs(np.hypot(p[:, 0], p[:, 1]) - 10).mean()
    assert off(c(t)) < 0.5 * off(track)
    # Each coordinate is the function fit with the same lam on those parameters:
    # the same Bezier ordinates.
    for d in range(3):
        s = bzspline.smoothing_spline(t, track[:, d], lam=c.lam)
        assert np.allclose(c.segments[:, :, d], s.segments[:, :, 1], rtol=0, atol=1e-11)
    # Pickled, the curve is the same curve.
    r = pickle.loads(pickle.dumps(c))
    assert np.array_equal(r(t), c(t))
    with pytest.raises(ValueError, match=r"weights\[1\]"):
        bzspline.smoothing_curve(track[:5], w=[1, -1, 1, 1, 1])
