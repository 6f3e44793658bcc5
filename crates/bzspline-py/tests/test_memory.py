"""The extension's allocator keeps a few freed blocks of 4 MiB or more for the
next large spline, and the last large spline dropped is kept whole to be
rebuilt as the next one of about its size: a build into kept memory gives the
bits of a build into new memory, a spline still in use is never taken, and
what is kept stays bounded however many sizes come and go."""

import hashlib
import os
import subprocess
import sys

import numpy as np

import bzspline

SCRIPT = """
import hashlib, sys
import numpy as np
import bzspline

def data(n, seed):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.5, 1.5, n))
    return x, np.sin(x / 50) + 0.1 * rng.normal(size=n)

def digest(s):
    return hashlib.sha256(np.ascontiguousarray(s.segments).tobytes()).hexdigest()

def rss():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096

{body}
"""


def run(body):
    out = subprocess.run([sys.executable, "-c", SCRIPT.format(body=body)],
                         capture_output=True, text=True, timeout=600,
                         env=dict(os.environ, RAYON_NUM_THREADS="2"))
    assert out.returncode == 0, out.stderr
    return out.stdout.split()


def test_a_build_into_kept_memory_has_the_bits_of_a_fresh_one():
    # In a process of its own: the first build of this size gets new memory.
    first, again, = run("""
x, y = data(600_001, 1)
fresh = digest(bzspline.Spline(x, y))
# Other data of the same size leave their blocks behind, then the first is
# built again into them.
for seed in (2, 3):
    u, v = data(600_001, seed)
    s = bzspline.Spline(u, v, alpha=np.full(600_000, 0.4))
    c = bzspline.Curve(np.column_stack([u, v]))
    del s, c
print(fresh, digest(bzspline.Spline(x, y)))
""")
    assert len(first) == 64
    assert again == first


def test_kept_memory_is_bounded():
    # Splines of sizes that cannot use each other's blocks (each over twice
    # the last), dropped in turn: kept without a bound they would hold 1.2 GB.
    grown, = run("""
start = rss()
for n in (1_000_000, 2_500_000, 6_000_000, 15_000_000):
    x, y = data(n, 4)
    s = bzspline.Spline(x, y)
    del s, x, y
print(rss() - start)
""")
    assert int(grown) < 600 * 2**20, f"{int(grown) / 2**20:.0f} MiB still held"


def test_the_bits_do_not_depend_on_what_ran_before_in_this_process():
    x = np.cumsum(np.random.default_rng(5).uniform(0.5, 1.5, 250_001))
    y = np.cos(x / 30)
    want = hashlib.sha256(bzspline.Spline(x, y).segments.tobytes()).hexdigest()
    for _ in range(3):
        junk = bzspline.Spline(x, -y)
        del junk
        got = hashlib.sha256(bzspline.Spline(x, y).segments.tobytes()).hexdigest()
        assert got == want


def test_a_spline_rebuilt_in_a_dropped_one_has_the_bits_of_a_fresh_one():
    # In a process of its own, so that the first build of each size has
    # nothing kept to use (the smaller cannot use the larger's spline, whose
    # knots are more than twice its own... until the larger is dropped).
    lines = run("""
x, y = data(300_001, 6)
small = digest(bzspline.Spline(x, y))
u, v = data(400_001, 7)
large = digest(bzspline.Spline(u, v))
# The large spline is kept: the small one is now rebuilt in it, and a large
# one of other data and alphas in the small one's.
print(small, large)
print(digest(bzspline.Spline(x, y)))
w = bzspline.Spline(u, -v, alpha=np.full(400_000, 0.6))
del w
print(digest(bzspline.Spline(u, v)))
# A refused build leaves what is kept as it was.
bad = y.copy(); bad[1234] = np.nan
try:
    bzspline.Spline(x, bad)
except ValueError as e:
    print("refused" if "1234" in str(e) else "unnamed")
print(digest(bzspline.Spline(x, y)))
""")
    small, large, *rest = lines
    assert rest == [small, large, "refused", small]


def test_a_spline_still_in_use_is_not_rebuilt():
    # The derivative shares its spline's pieces: dropping the spline leaves
    # them in use, and the next build of that size must not take them.
    got = run("""
x, y = data(300_001, 8)
s = bzspline.Spline(x, y)
d = s.derivative()
q = np.linspace(x[0], x[-1], 1001)
before = d(q).tobytes()
del s
t = bzspline.Spline(x, -y)
print(d(q).tobytes() == before, np.array_equal(t(q), -bzspline.Spline(x, y)(q)))
""")
    assert got == ["True", "True"]
