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


def _dense_se(x, y, w, lam, s):
    """sigma * sqrt(b^T M^-1 b) with M = B^T W B + lam R assembled from the
    method's basis splines (control values e_k) and R by two-point
    Gauss-Legendre on each piece (exact: S'' is linear there)."""
    n = len(x)
    basis = [bzspline.Spline(x, np.eye(n)[k]) for k in range(n)]
    B = np.array([b(x) for b in basis])                      # B[k, j] = B_k(x_j)
    g = np.array([-1, 1]) / np.sqrt(3)
    mid, half = (x[1:] + x[:-1]) / 2, (x[1:] - x[:-1]) / 2
    q = (mid[:, None] + half[:, None] * g).ravel()           # quadrature points
    qw = np.repeat(half, 2)
    D2 = np.array([b(q, 2) for b in basis])
    M = (B * w) @ B.T + lam * (D2 * qw) @ D2.T
    rss = np.sum(w * (y - s(x)) ** 2)
    sigma2 = rss / (np.count_nonzero(w) - s.dof)
    at = np.linspace(x[0], x[-1], 37)
    b = np.array([bb(at) for bb in basis])
    # The dense solve's own error grows with M's condition (1e8 on close knots).
    rtol = 1e-10 + 1e-15 * np.linalg.cond(M)
    return at, np.sqrt(sigma2 * np.einsum("ki,ki->i", b, np.linalg.solve(M, b))), rtol


def test_standard_errors_are_the_dense_posterior_variance():
    rng = np.random.default_rng(5)
    for n in (8, 15, 30):
        x = np.sort(rng.uniform(0, 3, n))
        y = np.cos(2 * x) + rng.normal(0, 0.2, n)
        w = rng.uniform(0.5, 2, n)
        s = bzspline.smoothing_spline(x, y, w, lam=0.01)
        at, want, rtol = _dense_se(x, y, w, 0.01, s)
        assert np.allclose(s.se(at), want, rtol=rtol, atol=0)
        lo, hi = s.band(at, level=0.95)
        assert np.allclose(hi - s(at), 1.959963984540054 * want, rtol=rtol)
        assert np.allclose(s(at) - lo, 1.959963984540054 * want, rtol=rtol)


def test_the_band_covers_the_truth_about_as_often_as_it_says():
    rng = np.random.default_rng(11)
    x = np.linspace(0, 1, 400)
    truth = np.sin(2 * np.pi * x) + 0.5 * x
    covered = [np.mean((lo <= truth) & (truth <= hi))
               for lo, hi in (bzspline.smoothing_spline(x, truth + rng.normal(0, 0.3, x.size)).band(x)
                              for _ in range(100))]
    assert 0.92 <= np.mean(covered) <= 0.985


def test_bands_survive_pickling_and_are_refused_where_there_are_none():
    x = np.linspace(0, 1, 50)
    y = np.sin(4 * x) + np.random.default_rng(2).normal(0, 0.1, 50)
    s = bzspline.smoothing_spline(x, y)
    t = pickle.loads(pickle.dumps(s))
    assert np.array_equal(t.se(x), s.se(x)) and s.se(x).shape == (50,)
    assert s.se(0.5).shape == () and s.se([[0.1, 0.2]]).shape == (1, 2)
    with pytest.raises(ValueError, match=r"x\[1\]: x = 2"):
        s.se([0.5, 2.0])
    with pytest.raises(ValueError, match="strictly between 0 and 1"):
        s.band(x, level=95)
    with pytest.raises(ValueError, match="smoothing_spline"):
        bzspline.Spline(x, y).se(0.5)
    with pytest.raises(ValueError, match="derivatives"):
        s.derivative().se(0.5)
    with pytest.raises(ValueError, match="no residual degrees of freedom"):
        bzspline.smoothing_spline(x, y, lam=0).band(x)


def test_robust_fits_shrug_off_outliers_and_match_the_command():
    x, y, truth = noisy(400, seed=7, sigma=0.1)
    rng = np.random.default_rng(8)
    bad = rng.choice(400, 4, replace=False)
    dirty = y.copy()
    dirty[bad] += rng.choice([-1, 1], 4) * rng.uniform(3, 6, 4)
    w = rng.uniform(0.5, 2, 400)
    err = lambda s: np.sqrt(np.mean((s(x) - truth) ** 2))
    clean = err(bzspline.smoothing_spline(x, y, w))
    plain = err(bzspline.smoothing_spline(x, dirty, w))
    r = bzspline.smoothing_spline(x, dirty, w, robust=True)
    assert err(r) < 1.3 * clean < plain
    assert r.robustness.shape == (400,) and np.all(r.robustness[bad] == 0)
    assert bzspline.smoothing_spline(x, y).robustness is None
    # The fit is the plain fit with its lam and the weights' products.
    p = bzspline.smoothing_spline(x, dirty, w * r.robustness, lam=r.lam)
    assert np.array_equal(p.control_values, r.control_values)
    # The command's --weights --robust gives the same numbers.
    table = "x,y,w\n" + "".join(
        f"{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in zip(x, dirty, w))
    got = fit(["--smooth", "auto", "--weights", "w", "--robust"], table)
    assert np.array_equal(r.control_values, np.array(got["values"]))
    assert np.array_equal(r.robustness, np.array(got["robustness"]))
    # Kept through pickling (dask ships splines so) and derivatives.
    q = pickle.loads(pickle.dumps(r))
    assert np.array_equal(q.robustness, r.robustness)
    assert np.array_equal(r.derivative().robustness, r.robustness)
    # A track with a jump, on its times.
    t = np.linspace(0, 3, 300)
    track = np.c_[np.cos(t), np.sin(t)] + rng.normal(0, 0.01, (300, 2))
    track[150] += [1.0, -1.0]
    c = bzspline.smoothing_curve(track, param=t, robust=True)
    assert c.robustness[150] == 0 and c.robustness.shape == (300,)
    assert np.hypot(*(c(t[150]) - [np.cos(t[150]), np.sin(t[150])])) < 0.02
    with pytest.raises(ValueError, match="at least 5"):
        bzspline.smoothing_spline(x[:4], y[:4], robust=True)


def test_closed_curves_smooth_round_their_loop_as_the_command_does():
    rng = np.random.default_rng(9)
    a = np.linspace(0, 2 * np.pi, 120, endpoint=False)
    truth = np.c_[5 * np.cos(a), 3 * np.sin(a)]
    ring = truth + rng.normal(0, 0.2, truth.shape)
    c = bzspline.smoothing_curve(ring, closed=True)
    assert len(c.segments) == 120 and c.lam > 0 and 1 < c.dof < 120
    table = "x,y\n" + "".join(f"{float(p)!r},{float(q)!r}\n" for p, q in ring)
    got = fit(["--closed", "--smooth", "auto"], table)
    assert np.array_equal(c.segments, np.array(got["segments"]))
    # On its parameters a closed fit lies closer to the ellipse than the data.
    t = np.arange(121) / 120.0
    e = bzspline.smoothing_curve(ring, param=t, closed=True)
    err = lambda p: np.abs(np.hypot(p[:, 0] / 5, p[:, 1] / 3) - 1).mean()
    assert err(e(t[:-1])) < 0.6 * err(ring)
    # A huge lam leaves the mean point.
    flat = bzspline.smoothing_curve(ring, lam=1e12, closed=True)
    assert np.allclose(flat.knot_points, ring.mean(axis=0), atol=1e-6)
