"""The README's Python examples run as written (from the repository root), so the README
cannot drift from the package. A Slurm example needs a cluster: it is only compiled (the
README links to docs/python.md for Slurm)."""

import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT

BLOCKS = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)


def test_the_readme_has_python_examples():
    # The FMU quickstart with fmpy, the package quickstart and the Dask LocalCluster example.
    assert len(BLOCKS) >= 3


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_python_block_runs(index, tmp_path):
    code = BLOCKS[index]
    if "SLURMCluster" in code:
        compile(code, f"README python block {index}", "exec")
        return
    script = tmp_path / f"readme_{index}.py"
    # Dask's LocalCluster starts worker processes: the code must run as a script whose
    # main module can be re-imported, so it is wrapped in a main guard.
    body = "".join("    " + line + "\n" for line in code.splitlines())
    script.write_text(f"def main():\n{body}\n\nif __name__ == '__main__':\n    main()\n")
    out = subprocess.run(
        [sys.executable, str(script)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
    )
    assert out.returncode == 0, f"README python block {index} failed:\n{code}\n{out.stderr}"
