import pathlib
import sys

import numpy as np
import pytest

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"
EPS = np.finfo(np.float64).eps


@pytest.fixture(scope="session")
def data_dir() -> pathlib.Path:
    return DATA


def venv_bin(name: str) -> str:
    """Path of an executable installed with the package (the environment's bin/)."""
    p = pathlib.Path(sys.prefix) / "bin" / name
    if not p.exists():
        pytest.fail(f"{name} is not installed in {p.parent}: pip install . should have put it there")
    return str(p)
