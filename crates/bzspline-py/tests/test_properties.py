"""Properties on generated inputs (hypothesis): the hull, the end points and
the agreement of the batch and the pointwise evaluation."""

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import bzspline  # noqa: E402

widths = st.lists(st.floats(0.01, 100.0), min_size=1, max_size=40)
values = st.floats(-1e6, 1e6, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(widths, st.data(), st.floats(1 / 3, 2 / 3))
def test_hull_ends_and_pointwise_agreement(w, data, alpha):
    x = np.concatenate([[0.0], np.cumsum(w)])
    y = np.array(data.draw(st.lists(values, min_size=len(x), max_size=len(x))))
    s = bzspline.Spline(x, y, alpha=alpha)
    q = np.linspace(x[0], x[-1], 257)
    v = s(q)
    span = np.abs(y).max() + 1.0
    assert v.min() >= y.min() - 1e-9 * span and v.max() <= y.max() + 1e-9 * span
    assert s(x[0]) == y[0] and s(x[-1]) == y[-1]
    for i in range(0, len(q), 16):
        assert s(q[i]) == v[i]
