"""What the sweep tests share: the example sweep and a bit-for-bit table comparison."""

import numpy as np
import pandas as pd

SWEEP = "examples/sweeps/6205-speed-displacement.toml"  # 18 quasi-static points
MEASUREMENTS = ["cpu [s]", "load_average"]  # raceway::sweep::MEASUREMENTS: the machine's


def assert_same_table(got: pd.DataFrame, ref: pd.DataFrame) -> None:
    """Equal columns, dtypes and values, floats bit for bit (but the machine measurements)."""
    assert list(got.columns) == list(ref.columns)
    got, ref = got.drop(columns=MEASUREMENTS), ref.drop(columns=MEASUREMENTS)
    pd.testing.assert_frame_equal(got, ref, check_exact=True)
    for c in got.columns:
        if got[c].dtype == np.float64:
            a, b = got[c].to_numpy(), ref[c].to_numpy()
            assert np.array_equal(a.view(np.uint64), b.view(np.uint64)), c
