"""The Python package against the method's defining conditions, scipy and
itself (pickling, threads, errors)."""

import pickle
import threading

import numpy as np
import pytest

import bzspline

TAU = np.arange(1.0, 12.0)
F = np.array([1, 3, 3, 1, 2, 7, 1.5, 1, 10, 2, 1.5])


def random_data(rng, n):
    x = np.cumsum(rng.uniform(0.1, 2.0, n))
    y = rng.normal(size=n) * 10
    return x, y


def test_paper_example_1_touches_every_leg_and_stays_in_the_hull():
    s = bzspline.Spline(TAU, F)
    assert s(1.0) == 1.0 and s(11.0) == 1.5
    mids = (TAU[:-1] + TAU[1:]) / 2
    assert np.allclose(s(mids), (F[:-1] + F[1:]) / 2, atol=1e-12)
    assert np.allclose(s(mids, nu=1), np.diff(F), atol=1e-12)
    dense = s(np.linspace(1, 11, 10001))
    assert dense.min() >= F.min() and dense.max() <= F.max()
    assert s.segments.shape == (10, 4, 2)
    assert np.array_equal(s.tangent_points, np.column_stack([mids, (F[:-1] + F[1:]) / 2]))


@pytest.mark.parametrize("seed", range(20))
def test_defining_conditions_on_random_data(seed):
    rng = np.random.default_rng(seed)
    x, y = random_data(rng, int(rng.integers(2, 60)))
    alphas = rng.uniform(1 / 3, 2 / 3, len(x) - 1)
    s = bzspline.Spline(x, y, alpha=alphas)
    h = np.diff(x)
    xk = x[1:] - alphas * h
    assert np.allclose(s(xk), alphas * y[:-1] + (1 - alphas) * y[1:], atol=1e-9 * np.abs(y).max())
    assert np.allclose(s(xk, 1), np.diff(y) / h, rtol=1e-9, atol=1e-9 * np.abs(y).max())
    # C1 at the interior knots, from both sides.
    eps = 1e-7 * h.min()
    assert np.allclose(s(x[1:-1] - eps, 1), s(x[1:-1] + eps, 1), rtol=1e-4, atol=1e-4)
    assert s(x[0]) == y[0] and s(x[-1]) == y[-1]


def test_through_passes_through_the_points():
    rng = np.random.default_rng(7)
    x, y = random_data(rng, 40)
    s = bzspline.Spline(x, y, through=True)
    assert np.allclose(s(x), y, atol=1e-9 * np.abs(y).max())
    assert np.allclose(s.knot_values, y, atol=1e-9 * np.abs(y).max())


def test_shapes_and_dtypes_follow_the_input():
    s = bzspline.Spline(TAU, F)
    for q in [2.5, [2.5, 3.5], np.full((3, 4), 2.5), np.full((2, 0), 1.0), np.float32(2.5)]:
        out = s(q)
        assert out.shape == np.shape(q) and out.dtype == np.float64
    strided = np.linspace(1, 11, 40)[::3]
    assert np.array_equal(s(strided), s(strided.copy()))


def test_out_receives_the_results():
    s = bzspline.Spline(TAU, F)
    q = np.linspace(1, 11, 101).reshape(101, 1)
    out = np.empty_like(q)
    assert s(q, 1, out=out) is out and np.array_equal(out, s(q, 1))
    with pytest.raises(ValueError, match="shape"):
        s(q, out=np.empty(101))
    with pytest.raises(ValueError):
        s(q, out=q)  # the input itself
    with pytest.raises(TypeError):
        s(q, out=np.empty((101, 1), dtype=np.float32))


def test_extrapolation_as_scipy():
    s = bzspline.Spline(TAU, F)
    assert np.isfinite(s(0.0)) and np.isfinite(s(12.0))
    n = bzspline.Spline(TAU, F, extrapolate=False)
    assert np.isnan(n(0.0)) and np.isnan(n(12.0)) and n(5.0) == s(5.0)
    assert np.isnan(n([0.5]))[0] and np.isnan(n.integrate(0.0, 2.0))
    c = bzspline.Spline(TAU, F, extrapolate="clamp")
    assert c(0.0) == 1.0 and c(20.0) == 1.5 and c(20.0, nu=1) == 0.0
    assert np.isnan(s(np.nan))
    # The library's names: 'nan' is False, 'extend' True, 'error' raises.
    q = np.array([0.0, 5.0, 12.0])
    assert np.array_equal(bzspline.Spline(TAU, F, extrapolate="nan")(q), n(q), equal_nan=True)
    assert np.array_equal(bzspline.Spline(TAU, F, extrapolate="extend")(q), s(q))
    e = bzspline.Spline(TAU, F, extrapolate="error")
    assert e(5.0) == s(5.0) and e.extrapolate == "error"
    with pytest.raises(ValueError):
        e(12.0)
    assert n.extrapolate is False and c.extrapolate == "clamp"


def test_scipy_pieces_are_the_same():
    scipy = pytest.importorskip("scipy")
    rng = np.random.default_rng(3)
    x, y = random_data(rng, 30)
    s = bzspline.Spline(x, y, alpha=0.4)
    q = np.linspace(x[0], x[-1], 1001)
    p, b = s.to_ppoly(), s.to_bpoly()
    assert isinstance(p, scipy.interpolate.PPoly) and isinstance(b, scipy.interpolate.BPoly)
    scale = np.abs(y).max()
    assert np.allclose(p(q), s(q), atol=1e-12 * scale)
    assert np.allclose(b(q), s(q), atol=1e-12 * scale)
    assert np.allclose(p(q, 1), s(q, 1), rtol=1e-9, atol=1e-9 * scale)
    assert np.isclose(s.integrate(x[0], x[-1]), p.integrate(x[0], x[-1]), rtol=1e-12)


def test_derivatives_extrema_and_integral():
    s = bzspline.Spline(TAU, F)
    d = s.derivative()
    q = np.linspace(1, 11, 101)
    assert np.array_equal(d(q), s(q, 1)) and np.array_equal(s.derivative(2)(q), s(q, 2))
    assert np.array_equal(s.derivative(4)(q), np.zeros_like(q))
    for x, y, kind in s.extrema():
        assert abs(s(x, 1)) < 1e-9 and kind in ("minimum", "maximum", "stationary")
    # The integral of the derivative is the change of the spline.
    assert np.isclose(s.integrate(2.0, 7.5), -s.integrate(7.5, 2.0))
    with pytest.raises(ValueError):
        d.integrate(1.0, 2.0)


def test_pickles_and_shares_between_threads():
    s = bzspline.Spline(TAU, F, alpha=0.6, extrapolate="clamp")
    for obj in [s, s.derivative(2)]:
        back = pickle.loads(pickle.dumps(obj))
        q = np.linspace(0, 12, 50)
        assert np.array_equal(back(q), obj(q)) and back.nu == obj.nu
    q = np.linspace(1, 11, 200_000)
    want = s(q)
    results = [None] * 4

    def work(i):
        results[i] = s(q)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(r, want) for r in results)


def test_bad_input_raises_value_error_naming_the_index():
    with pytest.raises(ValueError, match=r"knots\[2\]"):
        bzspline.Spline([0.0, 1.0, 1.0], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="NaN|finite"):
        bzspline.Spline([0.0, 1.0, 2.0], [1.0, np.nan, 3.0])
    with pytest.raises(ValueError, match=r"\[1/3, 2/3\]"):
        bzspline.Spline([0.0, 1.0, 2.0], [1.0, 2.0, 3.0], alpha=0.9)
    with pytest.raises(ValueError):
        bzspline.Spline([0.0, 1.0], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError):
        bzspline.Spline(np.zeros((2, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError):
        bzspline.Spline([0.0, 1.0], [1.0, 2.0], extrapolate="far")
    with pytest.raises(TypeError):
        bzspline.Spline(["a", "b"], [1.0, 2.0])
    with pytest.raises(ValueError):
        bzspline.Spline(TAU, F)(2.0, nu=-1)


def test_svg_path_ends_at_the_end_point():
    s = bzspline.Spline([0.0, 1.0, 2.0], [0.0, 1.0, 0.0])
    assert s.svg_path().startswith("M 0 0 C ") and s.svg_path().endswith(" 2 0")


@pytest.mark.parametrize("seed", range(10))
def test_antiderivative_is_scipys_integration_of_the_same_pieces(seed):
    scipy = pytest.importorskip("scipy")
    rng = np.random.default_rng(seed)
    x, y = random_data(rng, int(rng.integers(2, 60)))
    s = bzspline.Spline(x, y, alpha=rng.uniform(1 / 3, 2 / 3, len(x) - 1))
    f = s.antiderivative()
    assert f.nu == -1 and f(x[0]) == 0.0
    q = np.concatenate([x, rng.uniform(x[0] - 1, x[-1] + 1, 200)])
    want = s.to_ppoly().antiderivative()(q)
    scale = np.abs(want).max() + 1.0
    assert np.allclose(f(q), want, rtol=0, atol=1e-12 * scale * len(x))
    # F' = S, the antiderivative's derivative is the spline, differences are
    # integrals.
    assert np.array_equal(f(q, nu=1), s(q)) and np.array_equal(f.derivative()(q), s(q))
    a, b = rng.uniform(x[0], x[-1], 2)
    assert np.isclose(f(b) - f(a), s.integrate(a, b), rtol=0, atol=1e-12 * scale * len(x))
    # Of a derivative: the spline less its first value, as scipy.
    d = s.derivative().antiderivative()
    assert np.allclose(d(q), s(q) - s(x[0]), rtol=0, atol=1e-12 * scale)
    assert np.allclose(d.to_ppoly()(q), d(q), rtol=0, atol=1e-12 * scale)
    assert np.allclose(f.to_bpoly()(q), f(q), rtol=0, atol=1e-11 * scale)


def test_antiderivative_outside_and_its_errors():
    s = bzspline.Spline(TAU, F, extrapolate=False).antiderivative()
    assert np.isnan(s([0.0, 12.0])).all() and np.isfinite(s(TAU)).all()
    c = bzspline.Spline(TAU, F, extrapolate="clamp").antiderivative()
    end = c(11.0)
    assert np.isclose(c(13.0), end + 2 * F[-1]) and np.isclose(c(0.0), -F[0])
    assert np.isnan(s(np.nan))
    with pytest.raises(ValueError, match="to_ppoly"):
        s.antiderivative()
    with pytest.raises(ValueError):
        bzspline.Spline(TAU, F).antiderivative(nu=2)
    back = pickle.loads(pickle.dumps(c))
    q = np.linspace(-1, 13, 57)
    assert np.array_equal(back(q), c(q)) and back.nu == -1
    d = pickle.loads(pickle.dumps(bzspline.Spline(TAU, F).derivative().antiderivative()))
    assert np.array_equal(d(q), bzspline.Spline(TAU, F).derivative().antiderivative()(q))
