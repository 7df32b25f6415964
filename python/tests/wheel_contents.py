"""Check a built wheel: abi3 and manylinux in its name, the licence texts and the
third-party notices in its .dist-info/licenses/, byte for byte the repository root's files.

    python python/tests/wheel_contents.py target/wheels/raceway_bearing-...whl
"""

import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FILES = ["LICENSE-MIT", "LICENSE-APACHE", "THIRD-PARTY-NOTICES.md"]


def check(wheel: Path) -> None:
    assert "-abi3-" in wheel.name and "manylinux" in wheel.name, wheel.name
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        for f in FILES:
            found = [n for n in names if n.endswith(f".dist-info/licenses/{f}")]
            assert found, f"{wheel.name}: no .dist-info/licenses/{f} in {names}"
            assert z.read(found[0]) == (ROOT / f).read_bytes(), f"{f} differs from the root's"
        meta = next(n for n in names if n.endswith(".dist-info/METADATA"))
        text = z.read(meta).decode()
        for f in FILES:
            assert f"License-File: {f}" in text, f"METADATA does not list {f}"
        assert any(n.startswith("raceway/_raceway") and n.endswith(".so") for n in names)
    print(f"wheel {wheel.name}: {', '.join(FILES)} in .dist-info/licenses/")


if __name__ == "__main__":
    check(Path(sys.argv[1]))
