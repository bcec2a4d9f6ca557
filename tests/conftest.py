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
    config.addinivalue_line("markers", "full: an expensive reference sweep or process-level reliability run: "
                            "deselected by `make test`, run by `make test-full` (CI runs both)")


#: the tests of `make test-full` (the marker ``full``): each took 3 s or more of a 12-minute suite on a
#: loaded 2-core machine (the list and what each protects: docs/source/develop.md).  Named here rather
#: than decorated in place so that the list is one place; tests/test_full_marker.py checks each exists.
FULL = (
    "test_network.py::test_conservative_chain_energy_is_bounded_over_a_million_periods",
    "test_demo_run.py::test_the_whole_demo_runs_and_writes_its_figures",
    "test_junction_sweep.py::test_steps_edges_of_the_overdamped_junction_bracket_scipy_bisection",
    "test_friction_hard_cases.py::test_friction_slow_starts_hunted",
    "test_friction_hard_cases.py::test_friction_moving_start_first_turning_time",
    "test_sweep_follow.py::test_retrapping_hysteresis_against_scipy_continuation_by_hand",
    "test_sweep_follow.py::test_poincare_follow_keeps_one_asymmetric_orbit_against_scipy",
    "test_junction_lab.py::test_rsj_every_bias_on_a_step_is_reported_locked",
    "test_boundary_measures.py::test_forced_pendulum_at_1_66_has_three_attractors_and_wada_basins",
    "test_squid_dynamics.py::test_v_phi_curve_at_large_bias_matches_scipy",
    "test_squid_dynamics.py::test_noisy_overdamped_squid_matches_the_thermally_rounded_single_junction",
    "test_squid_dynamics.py::test_transfer_function_matches_a_scipy_difference_quotient",
    "test_squid_dynamics.py::test_overdamped_small_screening_squid_tends_to_the_single_junction_law",
    "test_squid_asymmetric.py::test_asymmetric_critical_current_matches_brute_force_maximisation_sweep",
    "test_squid_asymmetric.py::test_asymmetric_v_phi_curve_matches_scipy",
    "test_squid_asymmetric.py::test_asymmetric_iv_curve_matches_scipy_on_its_running_branch",
    "test_squid_sweep.py::test_sweep_from_rest_matches_scipy",
    "test_squid_sweep.py::test_sweep_of_the_overdamped_small_screening_squid_matches_the_closed_form",
    "test_squid_sweep.py::test_v_phi_running_branch_of_a_hysteretic_squid_matches_scipy",
    "test_attractor_agreement.py::test_default_map_agrees_with_scipy_long_runs_on_995_permille_of_stable_points",
    "test_double_motion.py::test_energy_bounded_over_1e5_swings",
    "test_double_sweep.py::test_flip_sweep_on_worker_processes_into_a_store_equals_flip_map",
    "test_attractors_recurrence.py::test_coarse_to_fine_map_matches_the_long_transient_run_on_995_permille_of_stable_points",
    "test_attractors_recurrence.py::test_grid_of_levels_gives_the_same_labels_whatever_the_threads_chunking_or_resume",
    "test_bifurcation_curves.py::test_retrapping_curve_against_scipy",
    "test_continuation.py::test_homoclinic_retrapping_torque_against_scipy_manifold",
    "test_continuation.py::test_liouville_det_along_every_branch",
    "test_continuation.py::test_retrapping_beyond_critical_damping_ends_on_snic_at_torque_one",
    "test_continuation.py::test_retrapping_just_below_critical_damping_is_a_homoclinic_within_1e8_of_one",
    "test_continuation.py::test_stewart_mccumber_small_damping_limit",
    "test_cycloid.py::test_damped_driven_against_mpmath_ode",
    "test_density.py::test_cdf_against_mpmath_time_integral",
    "test_dynamics_bad_input.py::test_long_work_is_interruptible_and_limited",
    "test_effects.py::test_friction_random_amplitudes_against_mpmath",
    "test_effects.py::test_friction_turning_points_against_mpmath",
    "test_fuzz.py::test_complete_integrals_and_nome",
    "test_fuzz.py::test_sweep_any_keyword",
    "test_fuzz_classes.py::test_long_work_stops_on_ctrl_c_and_has_a_bounded_identity",
    "test_fuzz_classes.py::test_programs_fail_on_one_line_with_a_documented_exit_status",
    "test_fuzz_classes.py::test_without_the_optional_extras_each_function_works_or_names_the_extra",
    "test_gravity.py::test_inverse_square_distance_near_one_hunted",
    "test_gravity.py::test_near_the_separatrix",
    "test_gravity.py::test_period_against_mpmath_energy_integral",
    "test_junction_steps.py::test_unlocked_error_bar_covers_a_long_average",
    "test_reference_grids.py::test_accuracy_page_grid_table_is_the_generated_one",
    "test_reliability_sweeps.py::test_cannot_stop_hybrid_cord_loop_stops_on_sigint",
    "test_reliability_sweeps.py::test_cannot_stop_long_spectra_stop_on_sigint",
    "test_reliability_sweeps.py::test_cannot_stop_the_process_stays_usable_after_a_cancelled_sweep",
    "test_reliability_sweeps.py::test_cli_tracebacks_full_disk_leaves_nothing_under_a_final_name",
    "test_reliability_sweeps.py::test_cli_tracebacks_run_and_sweep_succeed_with_room",
    "test_reliability_sweeps.py::test_destructive_write_wisdom_cli_is_one_line",
    "test_scene_corpus.py::test_both_programs_give_one_verdict_with_one_message",
    "test_scene_fuzz.py::test_both_programs_accept_or_refuse_alike_with_one_message",
    "test_spectrum.py::test_corrupt_or_foreign_wisdom_is_ignored_with_a_warning",
    "test_spectrum.py::test_missing_wisdom_is_silent_and_saved_wisdom_is_used",
    "test_sweep.py::test_boundary_points_uncertain_or_right",
    "test_sweep.py::test_final_well_random_points_against_scipy",
    "test_sweep.py::test_locked_and_running",
    "test_sweep.py::test_mean_velocity_against_scipy",
    "test_sweep.py::test_resume_after_kill",
    "test_sweep_cluster.py::test_cli_workers_closes_the_cluster_it_opens",
    "test_sweep_cluster.py::test_process_cluster_worker_killed_mid_run_result_complete_and_identical",
    "test_sweep_lyapunov.py::test_random_amplitudes_against_scipy_reference",
    "test_sweep_recheck.py::test_pendula_run_recheck_across_blocks_matches_python",
    "test_sweep_store.py::test_resume_after_seeded_random_damage_always_gives_the_in_memory_result",
    "test_sweep_store.py::test_resume_truncated_chunk_is_named_and_recomputed",
    "test_sweep_store.py::test_resume_unreadable_store_metadata_rebuilds_the_store",
    "test_sweep_store.py::test_two_cli_sweeps_on_the_same_output_second_exits_5_naming_the_store",
    "test_sweep_store.py::test_two_sweeps_on_the_same_out_second_refused_first_completes",
    "test_threads_spectrum.py::test_threads_hammering_spectra_of_many_lengths_match_serial_results",
    "test_verner87_coefficients.py::test_verner87_interpolant_satisfies_the_continuous_conditions_to_order_eight",
    "test_verner_coefficients.py::test_verner_interpolant_satisfies_the_continuous_conditions_to_order_eight",
)


#: single parametrisations of a test moved to `make test-full` (its other cases stay in `make test`):
#: the docs pages and docstrings whose examples compute the most (in a loaded run of the suite:
#: 99 s, 33 s and 32 s, a quarter of `make test`'s time; each under 30 s on an idle machine)
FULL_CASES = (
    "test_docs.py::test_python_blocks_of_the_docs_pages_run[guide/josephson.md]",
    "test_docs.py::test_python_blocks_of_the_docs_pages_run[guide/continuation.md]",
    "test_docs.py::test_docstring_examples[pendula.dynamics.branch_tree]",
)

#: every test node collected in this session, "file::name[case]" (test_full_marker checks FULL_CASES
#: against it)
COLLECTED = set()


def pytest_collection_modifyitems(config, items):
    """Mark the tests of FULL (every parametrisation) and of FULL_CASES (one each) with ``full``."""
    full, cases = set(FULL), set(FULL_CASES)
    for item in items:
        path = pathlib.Path(str(item.fspath)).name
        name = item.originalname if hasattr(item, "originalname") else item.name
        COLLECTED.add(f"{path}::{item.name}")
        if f"{path}::{name}" in full or f"{path}::{item.name}" in cases:
            item.add_marker(pytest.mark.full)


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
