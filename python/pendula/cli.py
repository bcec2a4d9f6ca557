"""The ``pendula`` command.

    pendula demo [-o out]        the main job: the default gallery of scenes, figures and tables
    pendula run SCENE.nml        one scene: CSV and PNG into an output folder
    pendula spectrum SCENE.nml   FFTW power spectra of a scene (CSV, log-power PNG)
    pendula bench [NAME ...]     benchmarks against scipy / GSL / numpy
    pendula wisdom               precompute FFTW plans once per machine (cache file)
    pendula accuracy elliptic    worst errors vs mpmath, beside scipy and GSL
    pendula accuracy integrators work-precision diagram and long-run energy (CSV, PNG)
    pendula accuracy grids       worst error per class of the stored random grids (the accuracy report's table)
    pendula --version            the installed version

A feature whose optional package is missing prints one line naming the extra
to install (``pip install 'pendula[sweep]'``) and exits with status 6
(pendula._optional.EXIT_MISSING_EXTRA).  Output into a pipe that closes early
(``pendula models | head -3``) ends quietly with status 0.

Every failure of every subcommand is one line on standard error, never a
traceback, with the exit status of docs/source/bad_input.rst: 2 bad scene or
arguments, 3 not implemented, 4 the computation failed (out of memory too),
5 the output cannot be written, 6 an optional package is missing, 130 Ctrl-C,
128 + signal for SIGTERM/SIGHUP.  (``PENDULA_TRACEBACK=1`` shows the traceback
of an unexpected error, for a bug report.)
"""

from __future__ import annotations

import argparse
import os
import math
import sys

import numpy as np

from ._checks import path as _checks_path
from ._files import gallery_dir
from ._optional import EXIT_MISSING_EXTRA, MissingExtraError, require


def packaged_data(name: str):
    """A reference file installed with the package (pendula/data; data/ in the repository)."""
    from importlib.resources import files

    return files("pendula") / "data" / name


#: exit status of Ctrl-C (128 + SIGINT, as shells report it)
EXIT_INTERRUPTED = 130


def exit_status(exc: BaseException) -> int:
    """The documented exit status of an error that ends a subcommand (docs/source/bad_input.rst):
    2 bad scene or argument, 3 not implemented, 4 the computation failed, 5 the output cannot
    be written, 6 an optional package is missing, 130 Ctrl-C."""
    from .scene import SceneError

    if isinstance(exc, KeyboardInterrupt):
        return EXIT_INTERRUPTED
    if isinstance(exc, MissingExtraError):
        return EXIT_MISSING_EXTRA
    if isinstance(exc, (SceneError, TypeError)):
        return 2
    if isinstance(exc, NotImplementedError):
        return 3
    if isinstance(exc, OSError):
        return 5
    return 4      # ValueError, ArithmeticError, MemoryError, RuntimeError, a worker that died ...


def _guarded(func, args) -> int:
    """Run a subcommand: every failure is one line on standard error with its exit status
    (:func:`exit_status`); a reader that closes the pipe early (``| head``) ends the output quietly."""
    import os

    command = f"pendula {getattr(args, 'command', None) or 'bench'}"
    try:
        status = func(args)
        sys.stdout.flush()  # a closed pipe shows here, not at interpreter exit
        return status
    except MissingExtraError as exc:
        print(f"pendula: {exc}", file=sys.stderr)
        return EXIT_MISSING_EXTRA
    except KeyboardInterrupt:
        print(f"{command}: interrupted (Ctrl-C); nothing half-written is left", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        # the reader has gone: send what remains in the buffer nowhere (Python's
        # documented recipe), so that the flush at exit does not fail again
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
        return 0
    except Exception as exc:       # noqa: BLE001 - the last resort: one line, never a traceback
        if os.environ.get("PENDULA_TRACEBACK"):
            raise
        code = exit_status(exc)
        if isinstance(exc, OSError) and exc.strerror:
            text = f"cannot write the output: {exc.filename + ': ' if exc.filename else ''}{exc.strerror}"
        else:
            text = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        print(f"{command}: {text}", file=sys.stderr)
        return code


def elliptic_table() -> list[tuple[str, float, float]]:
    """Hard cases of the elliptic kernel next to the exact values known in closed form."""
    from .elliptic import ellipe, ellipj, ellipk

    rows = []
    gamma14 = math.gamma(0.25)
    rows.append(("K(0) = pi/2", float(ellipk(0.0)), math.pi / 2))
    rows.append(("K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi))", float(ellipk(0.5)), gamma14**2 / (4 * math.sqrt(math.pi))))
    rows.append(("E(1/2) = pi^(3/2)/Gamma(1/4)^2 + Gamma(1/4)^2/(8 sqrt(pi))", float(ellipe(0.5)),
                 math.pi**1.5 / gamma14**2 + gamma14**2 / (8 * math.sqrt(math.pi))))
    rows.append(("K(mc = 1e-300) = ln 4 + 150 ln 10", float(ellipk(None, mc=1e-300)),
                 math.log(4.0) + 150 * math.log(10.0)))
    rows.append(("E(mc = 1e-300) = 1", float(ellipe(None, mc=1e-300)), 1.0))
    for m in (0.5, 0.99):
        k = float(ellipk(m))
        sn, cn, dn, am = ellipj(k, m)
        rows.append((f"sn(K|{m}) = 1", float(sn), 1.0))
        rows.append((f"cn(K|{m}) = 0", float(cn), 0.0))
        rows.append((f"dn(K|{m}) = sqrt(1-m)", float(dn), math.sqrt(1 - m)))
        sn, cn, dn, am = ellipj(k / 2, m)
        rows.append((f"sn(K/2|{m}) = 1/sqrt(1+sqrt(1-m))", float(sn), 1 / math.sqrt(1 + math.sqrt(1 - m))))
    u = 1000 * 4 * float(ellipk(0.3))
    sn, cn, dn, am = ellipj(u, 0.0)
    rows.append((f"sn(u = {u:.6g} | 0) = sin(u)", float(sn), math.sin(u)))
    sn, cn, dn, am = ellipj(3.0, 1.0)
    rows.append(("sn(3|1) = tanh 3", float(sn), math.tanh(3.0)))
    rows.append(("cn(3|1) = sech 3", float(cn), 1 / math.cosh(3.0)))
    sn, cn, dn, am = ellipj(3.0, None, mc=1e-300)
    rows.append(("sn(3 | mc=1e-300) = tanh 3 (to 1e-300)", float(sn), math.tanh(3.0)))
    rows.append(("dn(3 | mc=1e-300) = sech 3 (to 1e-300)", float(dn), 1 / math.cosh(3.0)))
    return rows


def print_elliptic_table() -> None:
    rows = elliptic_table()
    eps = np.finfo(float).eps
    print("pendula elliptic kernel: hard cases against closed forms")
    print(f"  {'case':62s} {'pendula':>24s} {'exact':>24s} {'|err|/eps':>9s}")
    for name, got, exact in rows:
        err = abs(got - exact) / (eps * max(1.0, abs(exact)))
        print(f"  {name:62s} {got:24.17g} {exact:24.17g} {err:9.1f}")


def _run_file(args, command: str, outputs: tuple | None = None) -> int:
    """Read a scene file (errors name the field, exit 2), run it, list the files."""
    import pathlib

    from .run import run_scene
    from .scene import Scene, SceneError

    if outputs is None:
        system = _run_system_file(args, command)   # &double, &foucault, &network: the kernel's reader and run
        if system is not None:
            return system
    try:
        scene = Scene.from_file(args.scene)
        if outputs:
            scene = scene.replace(outputs=outputs)
    except (SceneError, ValueError, OverflowError) as exc:   # a reader's bare ValueError too: one line, exit 2
        print(f"pendula {command}: {args.scene}: {exc}" if not isinstance(exc, SceneError)
              else f"pendula {command}: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"pendula {command}: cannot read {args.scene!r}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    # the exit codes of pendula-run: 3 model not implemented, 4 the computation
    # failed, 5 a write error; a message, never a traceback, and no partial file
    import warnings

    from .run import FiguresNotDrawn

    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", FiguresNotDrawn)
            files = run_scene(scene, args.output, stem=pathlib.Path(args.scene).stem, progress=not args.quiet)
    except NotImplementedError as exc:
        print(f"pendula {command}: {args.scene}: {exc}", file=sys.stderr)
        return 3
    except MissingExtraError:
        raise                          # one line naming the extra (exit 6), in _guarded
    except (ValueError, ArithmeticError, RuntimeError, MemoryError) as exc:
        text = str(exc) or "not enough memory"
        print(f"pendula {command}: {args.scene}: {text}", file=sys.stderr)
        return 4
    except OSError as exc:
        print(f"pendula {command}: cannot write into {args.output!r}: {exc.strerror or exc}", file=sys.stderr)
        return 5
    for f in files:
        print(f)
    skipped = [w for w in caught if issubclass(w.category, FiguresNotDrawn)]
    if skipped:      # the tables are written; the figures need the plot extra: say so, exit 6
        print(f"pendula {command}: {skipped[0].message}", file=sys.stderr)
        return EXIT_MISSING_EXTRA
    return 0


def _run_system_file(args, command: str) -> int | None:
    """Run the scene file of a system built by its own class (&double, &foucault, &network) as
    pendula-run does (the same table, the same exit codes: 2 bad scene, 4 the run failed, 5 a write
    error), plus its figure; None when the file is not one (the &scene reader takes it)."""
    import warnings

    from ._system_scenes import SystemRunError, run_system_scene, system_group
    from .run import FiguresNotDrawn
    from .scene import SceneError

    try:
        if not system_group(args.scene):
            return None
    except SceneError as exc:
        print(f"pendula {command}: {exc}", file=sys.stderr)
        return 2
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", FiguresNotDrawn)
            files = run_system_scene(args.scene, args.output)
    except SceneError as exc:
        print(f"pendula {command}: {exc}", file=sys.stderr)
        return 2
    except (SystemRunError, MemoryError) as exc:
        print(f"pendula {command}: {exc or 'not enough memory'}", file=sys.stderr)
        return 4
    except OSError as exc:
        print(f"pendula {command}: cannot write into {args.output!r}: {exc.strerror or exc}", file=sys.stderr)
        return 5
    for f in files:
        print(f)
    skipped = [w for w in caught if issubclass(w.category, FiguresNotDrawn)]
    if skipped:
        print(f"pendula {command}: {skipped[0].message}", file=sys.stderr)
        return EXIT_MISSING_EXTRA
    return 0


def cmd_run(args) -> int:
    return _run_file(args, "run")


def cmd_spectrum(args) -> int:
    return _run_file(args, "spectrum", outputs=("spectrum",))


#: the source texts of the default gallery, by the start of a scene's file name
GALLERY_SOURCES = (("cord_", "Garfinkel, \"On the motion of a simple pendulum\" (1957)"),
                   (("huygens_", "gravity_", "angle_"), "Prusa & Tuma, \"Everything you wanted to know about the "
                                                         "mathematical pendulum\" (2022)"),
                   ("", "Suzuki & Suzuki, \"Physics of simple pendulum\" (2008)"))


def _source_of(name: str) -> str:
    return next(text for prefix, text in GALLERY_SOURCES if name.startswith(prefix))


def _wrapped(words, width=100, indent="    ", sep=", ") -> list[str]:
    """The words joined by sep into lines of at most width characters."""
    lines, line = [], indent
    for w in words:
        if len(line) + len(w) + len(sep) > width and line.strip():
            lines.append(line[:-len(sep)])
            line = indent
        line += w + sep
    if line.strip():
        lines.append(line[:-len(sep)])
    return lines


def cmd_demo(args) -> int:
    """``pendula demo``: the default gallery; one screen of figures (``-v``: every table in full)."""
    import contextlib
    import io
    import json

    from .demos.cord import cord_demo
    from .demos import sweeps as sweep_demos
    from .demos.huygens import huygens_gallery
    from .run import run_scene
    from .scene import Scene

    for module in ("matplotlib", "xarray", "tqdm", "scipy"):  # figures; sweeps (scipy: their NetCDF files)
        require(module, "all", "pendula demo")
    verbose = args.verbose
    try:
        out = _checks_path(args.output, "--output")     # the one checker: '' is refused, never the current folder
    except (TypeError, ValueError) as exc:
        print(f"pendula demo: {exc}", file=sys.stderr)
        return 2
    if verbose:
        print_elliptic_table()
    else:
        rows = elliptic_table()
        eps = np.finfo(float).eps
        worst = max(abs(got - exact) / (eps * max(1.0, abs(exact))) for _, got, exact in rows)
        print(f"pendula demo -> {out.resolve()}   (pendula demo -v: every table in full)\n")
        print(f"elliptic functions: {len(rows)} hard cases (K, E, sn, cn, dn up to m = 1 - 1e-300) against "
              f"their closed forms: worst {worst:.1f} eps")
    scenes = sorted(p for p in gallery_dir().iterdir() if p.name.endswith(".nml"))
    sources = list(dict.fromkeys(_source_of(p.name) for p in scenes))
    print(f"\nthe default gallery: {len(scenes)} scenes from" + (" " + "; ".join(sources) if verbose else ""))
    written, harmonics = [], {}
    for p in scenes:
        scene = Scene.from_namelist(p.read_text(), source=p.name)
        said = io.StringIO()
        with contextlib.redirect_stdout(sys.stdout if verbose else said):
            files = run_scene(scene, out, stem=p.name[:-4], progress=not args.quiet)
        for line in said.getvalue().splitlines():   # "    stem: v0 = 1.9: odd harmonics above ...: 1, 3, 5"
            stem, label, _, lines = (line.strip().split(": ") + ["", "", ""])[:4]
            harmonics.setdefault(stem, []).append(f"{label}: {lines}")
        written += files
        if verbose:
            print(f"  {p.name:40s} {len(files)} file(s): " + ", ".join(f.name for f in files))
    if not verbose:
        for src in sources:
            names = [p.name[:-4] for p in scenes if _source_of(p.name) == src]
            print(f"  {src}:\n" + "\n".join(_wrapped(names)))
        for stem, rows in harmonics.items():
            print(f"  {stem}: the odd harmonics above 1e-6 of the fundamental's power\n"
                  + "\n".join(_wrapped(rows, sep="; ")))
    written += huygens_gallery(out)  # Huygens' clock, non-uniform gravity, density of the angle
    print()
    written += cord_demo(out, gallery_dir(), verbose=verbose)  # the flexible cord (Garfinkel)
    print("\nwhat accuracy costs in time: a short run (the damped pendulum, three tolerances;\n"
          "  the full study: pendula accuracy integrators)")
    said = io.StringIO()
    with contextlib.redirect_stdout(sys.stdout if verbose else said):
        integrator_study(out, 1e5, progress=not args.quiet and verbose, quick=True)
    if not verbose:
        record = json.loads((out / "work_precision.json").read_text())
        from .studies.explained import work_precision_sentences

        print("\n".join("  " + line for line in work_precision_sentences(record)))
    print()
    sweep_demos.run(out / "sweeps", small=True, verbose=verbose)
    print(f"\n{len(written)} gallery files, the integrator study and the sweeps written to {out.resolve()}")
    return 0


def cmd_accuracy(args) -> int:
    if args.what == "elliptic":
        import pathlib

        from .studies.accuracy import elliptic_report, print_report

        reference = args.reference or packaged_data("elliptic_reference.csv")
        if not pathlib.Path(reference).is_file():
            print(f"pendula accuracy: reference file {str(reference)!r} not found: pass --reference "
                  "(data/gen_elliptic_reference.py in the repository writes it)", file=sys.stderr)
            return 2
        try:
            report = elliptic_report(reference)
        except (ValueError, OSError) as exc:     # a reference that is not one: a bad input file, exit 2
            print(f"pendula accuracy: {exc}", file=sys.stderr)
            return 2
        print_report(report, markdown=args.markdown)
        return 0
    if args.what == "grids":
        import pathlib

        from .studies.accuracy import grids_markdown

        path = pathlib.Path(packaged_data("reference_grids.csv.gz"))
        if not path.is_file():
            print(f"pendula accuracy: {path} not found: reinstall pendula "
                  "(data/gen_reference_grids.py in the repository writes it)", file=sys.stderr)
            return 2
        print(grids_markdown(path))
        models = pathlib.Path(packaged_data("model_grids.csv.gz"))
        if models.is_file():
            from .studies.accuracy import model_grids_markdown

            print()
            print(model_grids_markdown(models))
        return 0
    return integrator_study(args.output, args.periods, progress=not args.quiet, quick=args.quick,
                            record_to=args.record, problems=args.problems)


def integrator_study(outdir, periods: float, progress: bool = True, quick: bool = False, record_to=None,
                     problems=None) -> int:
    """The work-precision study (pendula.studies.workprecision) and the long-run energy study; files into outdir."""
    from . import _checks
    from .studies.accuracy import long_run_energy, work_precision, write_long_run

    try:     # checked before the study runs: a bad value is one line, exit 2
        periods = _checks.real(periods, "--periods", 2.0, 1e8)
    except (TypeError, ValueError) as exc:
        print(f"pendula accuracy: {exc}", file=sys.stderr)
        return 2
    files = work_precision(outdir, quick=quick, progress=progress, record_to=record_to, problems=problems)
    res = long_run_energy(periods, progress=progress)
    files += write_long_run(res, outdir, periods)
    for f in files:
        print(f"  wrote {f}")
    return 0


def cmd_bench(args) -> int:
    from .studies.bench import main as bench_main

    return bench_main(args.rest)


def cmd_sweep(args) -> int:
    """pendula sweep SCENE -o OUT: the dataset (a Zarr store, resumable) and its figure."""
    return sweep_main(args)


def sweep_main(args) -> int:
    """``pendula sweep SCENE.nml -o OUT``: the dataset (the Zarr store OUT/sweep.zarr; with ``--netcdf``
    also OUT/sweep.nc) and its figure (OUT/sweep.png).

    One line on standard error for every failure, and the exit status of
    pendula-run: 2 bad scene or arguments (``--threads``, ``--workers``,
    ``--chunk-points`` out of range), 3 the scene's model is not one a sweep
    runs, 4 the computation failed, 5 the output cannot be written (OUT is a
    file, a device, read-only, a full disk, or another sweep is writing it);
    nothing is left under a final name after a failure (the resumable store
    stays).  A cluster started for ``--workers`` is closed on every path."""
    import contextlib

    from ._checks import count, path, threads as check_threads
    from ._files import atomic_path
    from ._store import StoreBusyError
    from .demos.sweeps import plot_sweep
    from .scene import Scene, SceneError
    from .sweeps import sweep

    def say(msg: str, code: int) -> int:
        print(f"pendula sweep: {msg}", file=sys.stderr)
        return code

    try:
        out = path(args.output, "--output")     # the one checker: '' is refused, never the current folder
        if getattr(args, "netcdf", False):     # before the sweep runs: a missing package is one line, exit 6
            require("scipy.io", "sweep", "pendula sweep --netcdf (NetCDF3 through SciPy)")
        workers = count(args.workers, "--workers", 0, 256)
        threads = check_threads(args.threads, "--threads")
        chunk_points = count(args.chunk_points, "--chunk-points", 1)
        scene = Scene.from_file(args.scene)
        if not scene.grid:
            raise SceneError(f"{args.scene}: field 'grid' is empty: a sweep scene names 1 to 3 axes")
        if out.exists() and not out.is_dir():
            raise NotADirectoryError(20, "is not a folder", str(out))
        with contextlib.ExitStack() as stack:
            client = None
            if workers:
                from ._cluster import local_client
                client = stack.enter_context(local_client(workers))   # closed, cluster and all, on leaving
            ds = sweep(scene, out=out, chunk_points=chunk_points, client=client, threads=threads,
                       progress=not args.quiet)
        files = [out / "sweep.zarr"]
        if getattr(args, "netcdf", False):
            with atomic_path(out / "sweep.nc") as tmp:
                ds.to_netcdf(tmp, engine="scipy")
            files.append(out / "sweep.nc")
        files.append(plot_sweep(ds, out / "sweep.png"))
    except (SceneError, ValueError, TypeError) as exc:
        return say(str(exc), 2)
    except NotImplementedError as exc:
        return say(f"{args.scene}: {exc}", 3)
    except StoreBusyError as exc:     # another sweep writes the same output folder
        return say(exc.strerror, 5)
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else f"{out}: "
        return say(f"cannot write the output: {where}{exc.strerror or exc}", 5)
    except (ArithmeticError, RuntimeError, MemoryError) as exc:
        return say(f"{args.scene}: {exc}", 4)
    except Exception as exc:    # noqa: BLE001 - the Dask cluster failed (a worker died: KilledWorker ...)
        if not type(exc).__module__.startswith(("distributed", "dask")):
            raise
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        return say(f"{args.scene}: the Dask cluster failed ({type(exc).__name__}: {first})", 4)
    st = ds.status.values
    print(f"pendula sweep: {st.size} points, {np.mean(st == 0) * 100:.1f} % decided -> "
          f"{', '.join(map(str, files))}")
    return 0


def cmd_models(args) -> int:
    """The models of the kernel's registry as a table."""
    from .systems import models

    rows = [("model", "selected by", "effects", "exact path with", "path", "ready")]
    for m in models():
        rows.append((m.name, m.selector, " ".join(m.effects) or "-",
                     "no effect" if not m.exact_with and m.path != "integrated" else
                     (" ".join(m.exact_with) if m.exact_with else "-"),
                     m.path, "yes" if m.implemented else "not yet"))
    _print_table(rows)
    _print_capabilities()
    return 0


def _print_table(rows) -> None:
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    for k, r in enumerate(rows):
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
        if k == 0:
            print("  ".join("-" * w for w in widths))


def _print_capabilities() -> None:
    """The capability table, one block per model: which tool honours which effect."""
    from .systems import models
    from .systems.contract import EFFECTS, capabilities

    caps = capabilities()
    print("\nWhat each tool honours, model by model (yes: changes the answer; -: refused, naming the field;"
          "\nlater: not implemented yet; need: one of these must be on; force: a user's force argument)")
    ms = models()
    for m in ms:
        # a model a Scene selects: every effect of the scene; one built by its class: its own effects
        effects = tuple(EFFECTS) if m.scene else m.effects
        rows = [("tool",) + effects]
        for c in caps:
            if c.system != m.name:
                continue
            rows.append((c.tool,) + tuple("yes" if e in c.honours else "later" if e in c.planned else "-"
                                          for e in effects))
            if c.needs:
                rows[-1] = tuple(x + "/need" if e in c.needs else x for x, e in zip(rows[-1], ("",) + effects))
        print(f"\n{m.name}: {m.summary}")
        _print_table(rows)
        if m.scene:
            scene_tools = {c.tool for c in caps for n in ms if n.scene and c.system == n.name}
            absent = sorted(scene_tools - {r[0] for r in rows[1:]})
            if absent:
                print(f"does not run the {m.name} model: {', '.join(absent)}")
        else:
            print(f"{m.name}'s fields: {' '.join(m.parameters)}\ntime scales: {m.time_scales}")


def main(argv=None) -> int:
    # figures are written to files, never shown: no display needed
    os.environ.setdefault("MPLBACKEND", "Agg")
    parser = argparse.ArgumentParser(prog="pendula", description="The nonlinear pendulum, exact and fast.")
    from ._version import __version__
    parser.add_argument("--version", action="version", version=f"pendula {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("demo", help="run the main job on its embedded default (the gallery of the source notes)")
    p.add_argument("-o", "--output", default="out", help="output folder (default: out)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bars")
    p.add_argument("-v", "--verbose", action="store_true", help="every table in full (default: one screen)")
    p.set_defaults(func=cmd_demo)
    p = sub.add_parser("run", help="run one scene file: CSV tables and PNG figures")
    p.add_argument("scene", help="scene file (namelist group &scene, or &double, &foucault, &network)")
    p.add_argument("-o", "--output", default="out", help="output folder (default: out)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=cmd_run)
    p = sub.add_parser("accuracy", help="measured accuracy against stored mpmath references")
    p.add_argument("what", choices=["elliptic", "integrators", "grids"])
    p.add_argument("-o", "--output", default="out", help="output folder for the integrator study")
    p.add_argument("--periods", type=float, default=1e5, help="length of the long energy run, in periods")
    p.add_argument("-q", "--quiet", action="store_true")
    p.add_argument("--reference", default=None,
                   help="reference CSV written by data/gen_elliptic_reference.py (default: the one installed "
                        "with pendula)")
    p.add_argument("--markdown", action="store_true", help="print a Markdown table")
    p.add_argument("--quick", action="store_true", help="integrators: the short form of the study (one problem)")
    p.add_argument("--record", default=None,
                   help="integrators: where to write the recorded run (default OUTPUT/work_precision.json)")
    p.add_argument("--problems", nargs="+", default=None,
                   help="integrators: only these problems (libration rotation damped torqued driven)")
    p.set_defaults(func=cmd_accuracy)
    p = sub.add_parser("spectrum", help="power spectra of a scene's theta(t): CSV and a log-power PNG")
    p.add_argument("scene", help="scene file (namelist group &scene)")
    p.add_argument("-o", "--output", default="out", help="output folder (default: out)")
    p.add_argument("-q", "--quiet", action="store_true")
    p.set_defaults(func=cmd_spectrum)
    p = sub.add_parser("models", help="the models pendula knows, the effects each accepts, which keep the exact path")
    p.set_defaults(func=cmd_models)
    # sweeps: the substance is in pendula.sweeps (the engine in pendula._sweep_engine)
    p = sub.add_parser("sweep", help="a sweep scene (grid + measure): OUT/sweep.zarr and OUT/sweep.png; resumes")
    p.add_argument("scene", help="scene file with 'grid' and 'measure'")
    p.add_argument("-o", "--output", default="out/sweep", help="output folder (chunks, dataset, figure)")
    p.add_argument("--threads", type=int, default=0, help="OpenMP threads (0: OMP_NUM_THREADS or all cores)")
    p.add_argument("--workers", type=int, default=0, help="run the chunks on a local Dask cluster of N worker processes (closed at the end)")
    p.add_argument("--chunk-points", type=int, default=20000, help="grid points per chunk")
    p.add_argument("--netcdf", action="store_true", help="also export the dataset as OUT/sweep.nc (NetCDF3)")
    p.add_argument("-q", "--quiet", action="store_true")
    p.set_defaults(func=cmd_sweep)
    p = sub.add_parser("bench", help="benchmarks against scipy, GSL and numpy", add_help=False)
    p.add_argument("rest", nargs=argparse.REMAINDER)
    p.set_defaults(func=cmd_bench)
    # --- spectra (spec): FFTW wisdom, handled in spectrum.py
    p = sub.add_parser("wisdom", help="precompute FFTW plans for this machine (saved in a cache file)")
    p.add_argument("sizes", nargs="*", type=int, help="record lengths (default: 2^6..2^20 and 3*2^k)")
    p.add_argument("--path", default=None, help="wisdom file (default: ~/.cache/pendula/fftw-wisdom)")
    p.set_defaults(func=lambda a: __import__("pendula.spectrum", fromlist=["wisdom_main"]).wisdom_main(a))
    # --- end spectra
    # --- spectra (spec): argparse's REMAINDER drops leading options ('bench --json F'), so pass them on
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["bench"]:
        return _guarded(cmd_bench, argparse.Namespace(rest=argv[1:]))
    # --- end spectra
    args = parser.parse_args(argv)
    from ._files import exit_on_sigterm
    exit_on_sigterm()     # SIGTERM/SIGHUP unwind like Ctrl-C: no temporary file is left
    return _guarded(args.func, args)


if __name__ == "__main__":
    sys.exit(main())
