"""The package's docstrings: numpy style on every public method, and their
examples run."""

import doctest
import inspect
import pathlib
import re

import pytest

import bzspline
import bzspline.geo


@pytest.mark.parametrize("cls", [bzspline.Spline, bzspline.Curve])
def test_every_method_says_what_it_returns(cls):
    assert "Parameters\n----------" in cls.__doc__ and "Examples\n--------" in cls.__doc__
    for name, member in inspect.getmembers(cls):
        if name.startswith("_") or isinstance(member, property) or not callable(member):
            continue
        doc = inspect.cleandoc(member.__doc__ or "")
        # A getter is documented by one line; methods in numpy style.
        if type(member).__name__ == "getset_descriptor":
            continue
        assert "Returns\n-------" in doc, f"{cls.__name__}.{name} has no Returns section"


@pytest.mark.parametrize("module", [bzspline, bzspline.geo, bzspline._core])
def test_examples_run(module):
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    tests = finder.find(module, globs={"np": __import__("numpy"), **vars(bzspline)})
    for t in tests:
        runner.run(t)
    assert runner.failures == 0
    if module is not bzspline.geo:
        assert runner.tries > 0


ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("page", ["README.md", "docs/python.md", "crates/bzspline-py/README.md"])
def test_the_guides_python_runs(page, monkeypatch):
    # Every ```python block of the page, in order, in one namespace, from the
    # repository's top folder (the paths the page names are relative to it).
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / page).read_text(), re.S)
    assert blocks, f"{page} shows no Python"
    monkeypatch.chdir(ROOT)
    namespace = {}
    for block in blocks:
        if "dask_geopandas" in block:
            pytest.importorskip("dask_geopandas")
        exec(compile(block, page, "exec"), namespace)  # noqa: S102
