"""Large constructions and smoothing fits on several threads: the same bits
for any number of threads, and a pool that survives ``fork`` (multiprocessing, dask's process
workers)."""

import hashlib
import multiprocessing
import os
import subprocess
import sys

import numpy as np

import bzspline

# Above the 131,072 legs from which the chunks of a system are spread over
# threads (from 65,537 it is solved in chunks).
N = 200_001

DIGEST = """
import hashlib, sys
import numpy as np
import bzspline
rng = np.random.default_rng(3)
x = np.cumsum(10 ** rng.uniform(-4, 4, {n}))
y = np.sin(x / x[-1] * 40) + rng.normal(size={n})
a = rng.choice([1 / 3, 2 / 3], {n} - 1)
s = bzspline.Spline(x, y, alpha=a)
c = bzspline.Curve(np.column_stack([x, y]), alpha=0.5)
h = hashlib.sha256(np.ascontiguousarray(s.segments).tobytes())
h.update(np.ascontiguousarray(c.segments).tobytes())
f = bzspline.smoothing_spline(x[:50_001], y[:50_001])
h.update(np.float64([f.lam, f.dof]).tobytes())
h.update(np.ascontiguousarray(f.segments).tobytes())
print(h.hexdigest())
"""


def digest(threads):
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    out = subprocess.run([sys.executable, "-c", DIGEST.format(n=N)], env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return out.stdout.strip()


def test_every_thread_count_gives_the_same_bits():
    one = digest(1)
    assert len(one) == 64
    assert digest(2) == one
    assert digest(16) == one


def data(seed):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.5, 1.5, N))
    return x, np.sin(x / 50) + 0.1 * rng.normal(size=N)


def build_in_child(queue):
    x, y = data(1)
    s = bzspline.Spline(x, y)
    queue.put(hashlib.sha256(s.segments.tobytes()).hexdigest())


def test_a_forked_child_builds_large_splines():
    # The parent's pool of threads does not cross fork: a child that used it
    # would wait for ever.
    x, y = data(1)
    want = hashlib.sha256(bzspline.Spline(x, y).segments.tobytes()).hexdigest()
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    child = ctx.Process(target=build_in_child, args=(queue,))
    child.start()
    child.join(120)
    if child.is_alive():
        child.kill()
        child.join()
        raise AssertionError("the forked child did not finish building")
    assert child.exitcode == 0
    assert queue.get(timeout=10) == want
