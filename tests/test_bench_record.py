"""The committed benchmark record renders the benchmark report's tables (not a timing test).

The tables of docs/source/reports/benchmarks.md are generated from
data/bench/bench.json; this checks that the record carries the machine and
versions, that every figure in it appears in the generated tables, and that the
page holds exactly what the generator makes from the record (so the report
cannot drift from the recorded run).
"""

import json
import pathlib

from pendula.studies.bench import readme_tables

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_recorded_run_has_machine_versions_and_every_figure_in_the_tables():
    record = json.loads((ROOT / "data" / "bench" / "bench.json").read_text())
    m = record["machine"]
    assert m["date_utc"] and m["cpu"] and m["versions"]["numpy"] and m["versions"]["pendula"]
    tables = readme_tables(record)
    assert set(record["results"]) >= {"elliptic", "exact", "integrators", "spectrum"}
    for rows in record["results"].values():
        for r in rows:
            assert str(r["what"]).replace("|", "\\|") in tables
            assert "ratio" not in r or f"{r['ratio']:.3g}" in tables


def test_benchmark_page_tables_are_the_generated_ones():
    record = json.loads((ROOT / "data" / "bench" / "bench.json").read_text())
    page = (ROOT / "docs" / "source" / "reports" / "benchmarks.md").read_text()
    block = page.split("<!-- bench:begin -->")[1].split("<!-- bench:end -->")[0]
    assert readme_tables(record).strip() in block
