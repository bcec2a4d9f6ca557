import pathlib
import signal
import sys

import numpy as np
import pytest

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"
EPS = np.finfo(np.float64).eps


def pytest_configure(config):
    """Children start with SIGINT at its default, however the runner was started.

    A shell without job control (``make test &``, nohup, cron) starts its children with SIGINT
    ignored, and an ignored disposition is inherited across exec: the Ctrl-C tests' children then
    never saw the signal they were sent (11 failures in the background).  A handled signal is reset
    to its default in an exec'd child, so restoring Python's handler here restores SIGINT for every
    child the tests start, and for the tests that interrupt this process itself."""
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture(scope="session")
def data_dir() -> pathlib.Path:
    return DATA


def venv_bin(name: str) -> str:
    """Path of an executable installed with the package (the environment's bin/)."""
    p = pathlib.Path(sys.prefix) / "bin" / name
    if not p.exists():
        pytest.fail(f"{name} is not installed in {p.parent}: pip install . should have put it there")
    return str(p)


def pendula_run_table(tmp_path, body: str):
    """Run pendula-run on a scene of the given body; return (its table as an array, the scene file)."""
    import subprocess

    import numpy as np

    f = tmp_path / "scene.nml"
    f.write_text("&scene\n" + body + "\n/\n")
    out = tmp_path / "o.csv"
    p = subprocess.run([venv_bin("pendula-run"), str(f), "-o", str(out)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    data = np.array([[float(x) for x in ln.split(",")] for ln in out.read_text().splitlines()
                     if ln and ln[0] not in "#t"])
    return data, f


def run_threads(targets, switch_interval: float = 1e-6) -> list:
    """Run each callable in its own thread with a tiny GIL switch interval (so the
    threads interleave as much as they can); return the exceptions they raised."""
    import sys
    import threading

    errors = []

    def wrap(f):
        def go():
            try:
                f()
            except BaseException as exc:  # noqa: BLE001 - handed back to the test
                errors.append(exc)
        return go

    threads = [threading.Thread(target=wrap(f)) for f in targets]
    old = sys.getswitchinterval()
    sys.setswitchinterval(switch_interval)
    try:
        for th in threads:
            th.start()
        for th in threads:
            th.join()
    finally:
        sys.setswitchinterval(old)
    return errors


def hard_case_errors(cls: str, set_: str) -> list[dict]:
    """The rows of data/hard_cases.csv.gz (data/gen_hard_cases.py: mpmath at the exact double inputs)
    of one class and set ('reproducer' or 'hunt'), each with pendula's value and its error in eps
    (pendula.studies.accuracy.hard_case_errors)."""
    from pendula.studies.accuracy import hard_case_errors as errors, load_hard_cases

    rows = [r for r in load_hard_cases(DATA / "hard_cases.csv.gz") if r["cls"] == cls and r["set"] == set_]
    assert rows, f"no {set_} rows of class {cls} in data/hard_cases.csv.gz"
    return errors(rows)


def worst_hard_case(errs: list[dict], bound) -> str:
    """'' when every row is within its bound (a number plus twice the condition number stored with the
    row: nonzero only for the rotation's density and CDF), else the worst row."""
    over = [e for e in errs if not e["err_eps"] <= bound + 2.0 * e["cond"]]
    if not over:
        return ""
    w = max(over, key=lambda e: e["err_eps"])
    return (f"{len(over)} of {len(errs)} rows over the bound; worst {w['func']}{tuple(w['args'])} "
            f"{w['quantity']}: {w['got']!r} against {w['ref']} ({w['err_eps']:.3g} eps)")


def assert_hard_cases(cls: str, set_: str, bound: float = 4.0) -> None:
    """Every row of a class and set of data/hard_cases.csv.gz within bound eps (plus twice its stored
    condition number); a hunt has more than 100 rows."""
    errs = hard_case_errors(cls, set_)
    assert set_ != "hunt" or len(errs) > 100, f"only {len(errs)} hunt rows of class {cls}"
    assert not worst_hard_case(errs, bound), worst_hard_case(errs, bound)
