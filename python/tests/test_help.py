"""The package's docstrings carry the reference (numpydoc): ``help()`` shows the parameters,
returns, errors and an example of every public function and class, and the examples run."""

import doctest
import pydoc

import pytest

import raceway
import raceway.dask

from conftest import ROOT

# (object, the numpydoc sections its help() must show)
DOCUMENTED = [
    (raceway.run, ["Parameters", "Returns", "Raises", "Examples"]),
    (raceway.quasi_static, ["Parameters", "Returns", "Raises", "Examples"]),
    (raceway.sweep, ["Parameters", "Returns", "Raises", "Examples"]),
    (raceway.bearing, ["Parameters", "Returns", "Raises", "Examples"]),
    (raceway.bearings, ["Returns", "Examples"]),
    (raceway.variables, ["Returns", "Examples"]),
    (raceway.dask.sweep, ["Parameters", "Returns", "Raises", "Examples"]),
    (raceway.Component, ["Parameters", "Raises", "Attributes", "Methods", "Examples"]),
    (raceway.State, ["Attributes", "Methods", "Examples"]),
    (raceway.Error, ["Attributes", "Examples"]),
    (raceway.Sweep, ["Parameters", "Raises", "Attributes", "Methods", "Examples"]),
    (raceway.QuasiStaticResult, ["Attributes"]),
    (raceway.RollerQuasiStaticResult, ["Attributes"]),
    (raceway.shaft, ["Parameters", "Returns", "Raises", "Examples"]),
]


@pytest.mark.parametrize("obj,sections", DOCUMENTED, ids=lambda o: getattr(o, "__name__", ""))
def test_help_shows_numpydoc_sections(obj, sections):
    text = pydoc.render_doc(obj, renderer=pydoc.plaintext)
    for section in sections:
        assert f"{section}\n" in text and "-" * len(section) in text, (obj, section)


def test_docstring_examples_run(monkeypatch):
    # The examples use paths relative to the repository root, as the README's do.
    monkeypatch.chdir(ROOT)
    objs = [o for o, _ in DOCUMENTED]
    failed = attempted = 0
    for obj in objs:
        for test in doctest.DocTestFinder(recurse=False).find(obj, globs={"raceway": raceway}):
            r = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS).run(test)
            failed += r.failed
            attempted += r.attempted
    assert attempted >= 10 and failed == 0
