"""Command line: stressfields run | list | describe | validate | schema | export | hash | compare | suite | bench.

Conventions: results go to stdout and everything else (progress, notes, errors) to stderr; progress
bars only when stderr is a terminal; `--json` gives `list`, `describe`, `validate` and `hash` as one
JSON document; a recipe path `-` reads the recipe from standard input; `-o -` is refused (NetCDF and
Zarr need a file or directory); no colour is ever written, so NO_COLOR holds whatever it says.

The heavy libraries (xarray, dask, the writers) are imported inside the commands that compute or
write: `--help`, `list`, `describe`, `schema` and `validate` need only the scenario declarations,
which import no kernel and no scipy (``physics/names.py``). Measured: `stressfields describe conical`
took 1.19 s with everything imported at the top, 0.17-0.31 s now (medians of 5 on a 2-core machine
at load 3-4); tests/test_lazy_imports.py holds what is imported.
"""
from __future__ import annotations

import argparse
import contextlib
import gc
import logging
import os
import signal
import sys
import threading
import time
from pathlib import Path

# the dask threads are the run's parallelism: OpenBLAS's own threads (started with NumPy, used by
# the few LAPACK calls at singular points) only spin beside them and cost CPU (docs/bench/tuning.md).
# Set before NumPy is first imported; a value the user set is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from .errors import OutputError, RecipeError
from .output.options import DTYPES, NONFINITE
from .version import __version__

#: the unit conversions of `compare` (comparison.UNITS, held equal by tests/test_compare.py)
COMPARE_UNITS = ("Pa", "kPa", "MPa", "GPa", "m", "mm", "um", "N", "1")

LOCAL_SCHEDULERS = ("threads", "synchronous", "processes")


#: signals that end a run like Ctrl-C (schedulers, `timeout` and `docker stop` send TERM; a closed
#: terminal sends HUP), with the exit code of a process killed by them (128 + number)
SIGNALS = {signal.SIGTERM: "SIGTERM", signal.SIGHUP: "SIGHUP"}


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    previous = _catch_signals()
    try:
        code = args.func(args)
        sys.stdout.flush()      # a closed pipe must show here, not at the interpreter's exit
        return code
    except KeyboardInterrupt:
        print("interrupted; no partial output was left", file=sys.stderr)
        return 130
    except Terminated as exc:
        print(f"terminated by {SIGNALS[exc.signum]}; no partial output was left", file=sys.stderr)
        return 128 + exc.signum
    except BrokenPipeError:
        # the reader went away (`stressfields describe X | head -1`): say so once, and keep the
        # interpreter's final flush of stdout from raising again
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        print("error: output pipe closed before everything was written", file=sys.stderr)
        return 2
    except Exception as exc:        # last: a handler's re-raise does not reach the clauses after it
        if not _user_error(exc):
            raise
        print(f"error: {exc}", file=sys.stderr)
        return 2
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def entry() -> None:
    """The `stressfields` command: `main`, then the exit. After an interrupt (Ctrl-C, SIGTERM, SIGHUP)
    the writers have removed their temporaries; the process then ends at once rather than joining
    worker threads at interpreter exit, one of which may wait forever on a lock the interrupted
    main thread held (seen once in 40 killed runs in parts mode: 60 s without exiting)."""
    code = main()
    if code == 130 or code - 128 in SIGNALS:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)


class UsageError(ValueError):
    pass


def _user_error(exc: Exception) -> bool:
    """A problem of the input, said in one line: a CompareError can only come from a loaded
    comparison.py, so the check does not import it (and with it xarray) for the commands that need none."""
    compare = sys.modules.get(f"{__package__}.comparison")
    return isinstance(exc, (OutputError, RecipeError, UsageError)) or (
        compare is not None and isinstance(exc, compare.CompareError))


class Terminated(BaseException):
    """Raised in the main thread by SIGTERM/SIGHUP, so the writers remove their temporaries as for Ctrl-C."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


def _catch_signals() -> dict:
    if threading.current_thread() is not threading.main_thread():
        return {}           # signal handlers can only be set from the main thread (an embedding program's)
    return {signum: signal.signal(signum, _terminate) for signum in SIGNALS}


def _terminate(signum, frame):
    for other in SIGNALS:   # a second signal must not interrupt the clean-up of the first
        signal.signal(other, signal.SIG_IGN)
    raise Terminated(signum)


def _parser() -> argparse.ArgumentParser:
    from .api import PARTS_ABOVE

    p = argparse.ArgumentParser(prog="stressfields", description="Reference datasets of contact-mechanics "
                                "fields: recipe (TOML) -> CF NetCDF.")
    p.add_argument("--version", action="version", version=f"stressfields {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="generate the datasets of one or more recipes")
    run.add_argument("recipes", nargs="+", type=Path, help="recipe TOML file(s); - reads one from standard input "
                     "(written to OUT_DIR/stdin.nc without -o)")
    run.add_argument("-o", "--output", type=Path, help="output NetCDF file, or a Zarr store if it ends in "
                     ".zarr (one recipe only)")
    run.add_argument("-d", "--out-dir", type=Path, default=Path("out"),
                     help="directory for <recipe name>.nc when -o is not given (default: out)")
    run.add_argument("--chunks", default="", help="chunk sizes per dimension, e.g. x=1000,mu=1")
    run.add_argument("--scheduler", default="threads",
                     help="dask scheduler: threads (default), synchronous, processes, or the address of a "
                          "dask.distributed scheduler (tcp://host:8786)")
    run.add_argument("--overwrite", action="store_true", help="replace existing output files")
    run.add_argument("--plot", action="store_true", help="also write a quick-look PNG beside each file "
                     "(needs matplotlib: pip install 'stressfields[plot]')")
    talk = run.add_mutually_exclusive_group()
    talk.add_argument("-q", "--quiet", action="store_true", help="nothing on stderr but errors")
    talk.add_argument("-v", "--verbose", action="store_true", help="also the chunks, and each file's size, time and "
                      "content hash")
    run.add_argument("--resume", action="store_true", help="finish an interrupted run from its finished parts "
                     "(OUT.nc.parts/); implies writing in parts")
    run.add_argument("--parts", action="store_true", help="write in resumable parts along the first dimension "
                     f"(automatic above {PARTS_ABOVE:.0e} points)")
    run.add_argument("--dtype", choices=DTYPES, default=None,
                     help="storage of the float fields (overrides the recipe's output.dtype): float64 (default, "
                     "exact) or float32 (half the size; adds a "
                     "relative rounding error of 6e-8, 1.4e-45 absolute below 1.2e-38, noted in each field's "
                     "stressfields_accuracy)")
    run.add_argument("--compression", type=int, choices=range(10), metavar="0-9", default=None,
                     help="compress at this level: zlib with shuffling (NetCDF), Blosc/zstd (Zarr); 0 none "
                     "(default: none for NetCDF, zarr's default compressor for Zarr)")
    run.add_argument("--nonfinite", choices=NONFINITE, default=None,
                     help="+-inf and NaN at singular points (overrides the recipe's output.nonfinite): keep "
                     "(default), nan (+-inf -> NaN), or fill (both "
                     "stored as the variable's _FillValue, read back as missing); the validity flags always "
                     "say why")
    run.add_argument("--dry-run", action="store_true", help="print dimensions, points, output size and an "
                     "estimated time (from a small sample), and write nothing")
    run.add_argument("--no-space-check", dest="space_check", action="store_false",
                     help="start even if the output's estimated size exceeds the free space of its file system")
    _allow_read_option(run)
    run.set_defaults(func=_run)

    lst = sub.add_parser("list", help="list the scenarios")
    lst.set_defaults(func=_list)

    desc = sub.add_parser("describe", help="parameters and variables of a scenario")
    desc.add_argument("scenario")
    desc.set_defaults(func=_describe)

    val = sub.add_parser("validate", help="check recipes without computing anything")
    val.add_argument("recipes", nargs="+", type=Path, help="recipe TOML file(s); - reads one from standard input")
    _allow_read_option(val)
    val.set_defaults(func=_validate)

    ex = sub.add_parser("example", help="the recipes shipped with the package: their names, or one recipe's TOML "
                        "(stressfields example hertz_subsurface | stressfields run - -o hertz.nc)")
    ex.add_argument("name", nargs="?", help="a name from `stressfields example`")
    ex.set_defaults(func=_example)

    sch = sub.add_parser("schema", help="print data_schema.md (derived from the scenario declarations)")
    sch.set_defaults(func=_schema)

    exp = sub.add_parser("export", help="convert a Zarr store (e.g. from a cluster run) to NetCDF, or a dataset to "
                         "VTU for ParaView (-o OUT.vtu; pip install 'stressfields[fe]'), atomically; or with --layout, "
                         "a file to an ML-ready directory split by its recipe's [splits]")
    exp.add_argument("store", type=Path)
    exp.add_argument("-o", "--output", type=Path, required=True)
    exp.add_argument("--overwrite", action="store_true")
    exp.add_argument("--layout", choices=("well", "parquet"), default=None,
                     help="write the directory OUTPUT instead: well (The Well: data/{train,valid,test}/*.hdf5, "
                     "stats.yaml, metadata YAML) or parquet (one row per point; pip install 'stressfields[ml]'); "
                     "both with a Croissant card")
    exp.set_defaults(func=_export)

    hsh = sub.add_parser("hash", help="recompute a file's content hash and check it against the stored one")
    hsh.add_argument("files", nargs="+", type=Path)
    hsh.set_defaults(func=_hash)
    for command in (lst, desc, val, hsh):
        command.add_argument("--json", action="store_true", help="one JSON document on stdout")

    cmp = sub.add_parser("compare", help="compare your nodal values (an FE model's: CSV, NetCDF, Exodus II, VTU/VTK, "
                         "XDMF, MED, Gmsh) with the reference at the same points: exit 0 within --tolerance, 1 "
                         "beyond it, 2 bad input")
    cmp.add_argument("recipe", type=Path, help="recipe TOML file (its [points] and the coordinates the nodes give "
                     "are replaced by the nodes)")
    cmp.add_argument("user_data", type=Path, nargs="+", help="file(s) of nodes: CSV with a header such as "
                     "x[mm],y[mm],z[mm],sigma_xx[MPa] (also X(mm), Node Label, S-S11; units: any pint converts, "
                     "e.g. " + ", ".join(COMPARE_UNITS[:4]) + ", N/mm^2, psi; none: the scenario's unit), NetCDF "
                     "with units attributes, Exodus II, or VTU/VTK/XDMF/MED/Gmsh (pip install 'stressfields[fe]'); "
                     "several files: a mesh sequence, coarse to fine (convergence table)")
    cmp.add_argument("-o", "--output", dest="report_dir", type=Path, required=True,
                     help="report folder (comparison.nc, report.md, report.json, comparison.png), published "
                     "whole when complete: a new or empty folder, or a previous report with --overwrite")
    cmp.add_argument("--tolerance", default=None,
                     help="largest max |difference| / scale (p_m for stresses) a variable may have, or limits of "
                          "any statistic: max, rms, p50, p95, p99, l2, wl2, wrms, energy (e.g. rms=1e-3,max=0.05); "
                          "default: report only, exit 0")
    cmp.add_argument("--variables", nargs="+", default=None, help="compare only these value columns")
    cmp.add_argument("--overwrite", action="store_true", help="replace the report files")
    cmp.add_argument("--no-plot", action="store_true", help="no PNG (faster)")
    cmp.add_argument("--step", type=int, default=None, help="Exodus II: this time step only (from 1; default: "
                     "every step, each compared)")
    cmp.add_argument("--units", default=None, help="units of a format that carries none (VTU, Exodus II, ...): "
                     "length=mm,stress=MPa,force=N (displacement=um if it differs from length)")
    cmp.add_argument("--z-up", action="store_true", help="the model's body lies at z <= 0: z, sigma_xz, sigma_yz, "
                     "u_z (and sigma_rz) change sign")
    cmp.add_argument("--axisymmetric", action="store_true", help="a 2-D (r, z) model: a 2-D mesh's second "
                     "coordinate is z; columns r, sigma_rr, sigma_tt (sigma_thetatheta), sigma_rz, u_r")
    cmp.add_argument("--body", type=int, choices=(1, 2), default=1, help="2: the nodes belong to the second of two "
                     "identical bodies (the mirror image, z -> -z, tangential traction reversed); a column 'body' "
                     "gives it per node")
    cmp.add_argument("--exclude-edge", type=float, default=None, metavar="W", help="report the nodes within W a of "
                     "the contact edge, the stick edge (or the cone tip) apart, outside the verdict")
    cmp.add_argument("--remove-rigid-offset", action="store_true", help="subtract the mean displacement difference "
                     "(a finite model's rigid offset) from u_x, u_y, u_z before comparing")
    cmp.add_argument("--scale", choices=("p0", "p_m"), default=None, help="the file's stresses are divided by p0 "
                     "(the pressure at the centre) or by p_m")
    cmp.add_argument("--h", default=None, help="mesh sizes of a mesh sequence, one per file (default: N^(-1/d))")
    cmp.set_defaults(func=_compare)

    ste = sub.add_parser("suite", help="the published reference suite (suite/ of a clone): build it into a "
                         "directory, or verify a built one against the registered hashes")
    ste.add_argument("action", choices=("build", "verify"), help="build: write every dataset (skipping those "
                     "present whose hashes verify), key_values.csv and catalog.yaml; verify: recompute every hash")
    ste.add_argument("directory", type=Path)
    ste.set_defaults(func=_suite)

    bench = sub.add_parser("bench", help="chart accuracy against run time for every method (not a test)")
    bench.add_argument("-d", "--out-dir", type=Path, default=Path("docs/bench"),
                       help="where the results NetCDF and the PNG chart go (default: docs/bench)")
    bench.add_argument("--quick", action="store_true", help="fewer repeats and smaller cases")
    bench.add_argument("--peers", action="store_true",
                       help="also time ContactMechanics' FFT solver on the Hertz problem "
                            "(pip install 'stressfields[bench]')")
    bench.set_defaults(func=_bench)
    return p


def _allow_read_option(parser) -> None:
    parser.add_argument("--allow-read", action="append", default=[], type=Path, metavar="DIR",
                        help="also read [points] files from inside DIR (repeatable); by default a points file "
                        "must lie inside its recipe's folder, symbolic links resolved")


def _compare(args) -> int:
    """The comparison's report folder (fe/command.py), published whole (`comparison.publish_report`);
    the folder is checked before anything is computed."""
    from .fe.command import run

    _no_stdout(args.report_dir)
    # no dask scheduler: the reference is computed now and the report is in memory (comparison.py)
    return run(args, plotting=not args.no_plot and _has_matplotlib())


def _no_stdout(output: Path | None) -> None:
    """Refuse ``-o -``: the outputs are NetCDF files, Zarr stores and report folders, not a stream."""
    if output is not None and str(output) == "-":
        raise UsageError("-o -: output cannot go to stdout (NetCDF and Zarr need a file or directory); "
                         "give a path such as -o out.nc")


def _has_matplotlib() -> bool:
    import importlib.util

    return importlib.util.find_spec("matplotlib") is not None


def _export(args) -> int:
    from .output.formats import export

    _no_stdout(args.output)
    if not args.store.exists():
        raise UsageError(f"{args.store}: no such file or store")
    if args.layout:
        from .mlexport import export_layout

        export_layout(args.store, args.output, args.layout, overwrite=args.overwrite)
        return 0
    if args.output.suffix.lower() == ".vtu":      # for ParaView: fe/vtu.py (the optional fe extra)
        from .fe.vtu import export_vtu

        export_vtu(args.store, args.output, overwrite=args.overwrite)
        return 0
    export(args.store, args.output, overwrite=args.overwrite)
    return 0


def _hash(args) -> int:
    from .output.formats import file_hash

    bad, records = 0, []
    for path in args.files:
        if not path.exists():
            raise UsageError(f"{path}: no such file")
        if not (path.is_file() or path.is_dir()):      # a FIFO blocks forever, a device reads forever
            raise UsageError(f"{path}: not a regular file or a Zarr store")
        try:
            digest, stored = file_hash(path)
        except Exception as exc:      # any reader's failure on a damaged or foreign file
            raise UsageError(f"{path}: not a readable NetCDF file or Zarr store "
                             f"({type(exc).__name__}: {str(exc)[:200]})") from None
        status = "unverified" if stored is None else "ok" if stored == digest else "mismatch"
        bad += status != "ok"
        records.append({"file": str(path), "sha256": digest, "stored": stored, "status": status})
        if args.json:
            continue
        if stored is None:
            print(f"{path}: {digest} unverified (no stored hash to check)")
        elif stored == digest:
            print(f"{path}: {digest} ok")
        else:
            print(f"{path}: {digest} MISMATCH (stored {stored})")
    if args.json:
        _json(records)
    return 1 if bad else 0


def _suite(args) -> int:
    """Exit 0 when every dataset matches the registry, 1 when one differs (each said on stderr), 2 on
    bad input (no suite, a directory that cannot be made)."""
    from .suite import build, verify

    if args.action == "verify" and not args.directory.is_dir():
        raise UsageError(f"{args.directory}: no such directory (build the suite into it first)")
    if args.action == "build":
        _check_out_dir(args.directory, "DIRECTORY")
    say = lambda line: print(line, file=sys.stderr)
    problems = (build if args.action == "build" else verify)(args.directory, say=say)
    for problem in problems:
        print(f"MISMATCH {problem}", file=sys.stderr)
    print(f"{args.action}: {'ok' if not problems else f'{len(problems)} dataset(s) differ from the registry'}")
    return 1 if problems else 0


def _bench(args) -> int:
    return bench_harness().run(out_dir=args.out_dir, quick=args.quick, peers=args.peers)


def bench_harness():
    """benchmarks/harness.py of the clone this package is installed from, loaded by path."""
    harness = Path(__file__).resolve().parents[1] / "benchmarks" / "harness.py"
    if not harness.exists():
        raise UsageError("the benchmark harness lives in the repository (benchmarks/harness.py): run "
                         "`stressfields bench` from a clone installed with pip install -e")
    import importlib.util

    spec = importlib.util.spec_from_file_location("stressfields_bench_harness", harness)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module         # its dataclasses look their module up while it loads
    spec.loader.exec_module(module)
    return module


def _keep_freed_memory() -> None:
    """Keep the large temporaries of the kernels in the process heap instead of mapping and
    unmapping them for every block (glibc; elsewhere nothing changes). Measured, a 1e8-point run of
    eleven fields in parts: 61.8 s instead of 77.0 s wall, 32 s instead of 51 s of system time, peak
    memory 1.25 GB instead of 0.68 GB. One arena for every thread: a worker thread's own arena grows
    in heaps of at most 64 MB, which a kernel's temporaries on a 1e6-point block overflow, and what
    overflows is mapped and unmapped again each time (a 3.6e7-point run of eleven fields in parts:
    system time 4.3 s instead of 11.8 s, 1.5e5 page faults instead of 6.7e5, wall 12.6 s instead of
    18.6 s, peak memory 1.26 GB instead of 2.04 GB). The blocks are few and large, so the threads
    hardly ever wait on the arena's lock."""
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6")
        m_trim_threshold, m_mmap_threshold, m_arena_max = -1, -3, -8
        libc.mallopt(m_mmap_threshold, 1 << 30)
        libc.mallopt(m_trim_threshold, (1 << 31) - 1)
        libc.mallopt(m_arena_max, 1)
    except (OSError, AttributeError):
        pass


def _run(args) -> int:
    """Parse, then hand every recipe to the front door (`api.plan`: recipe, chunking, target, output
    options, parts), check the free space of them all (`api.check_space`), and write them one by one."""
    from .api import check_space, plan

    _no_stdout(args.output)
    if args.output and len(args.recipes) > 1:
        raise UsageError("-o/--output takes one recipe; use --out-dir for several")
    if sum(str(p) == "-" for p in args.recipes) > 1:
        raise UsageError("- (standard input) can be given once")
    chunks = _parse_chunks(args.chunks)
    if args.plot and not args.dry_run:
        _check_plotting()
    out_dir_ready = args.output is not None or _check_out_dir(args.out_dir)
    runs = []
    for path in args.recipes:      # validate everything before computing anything
        target = args.output or args.out_dir / f"{'stdin' if str(path) == '-' else path.stem}.nc"
        run = plan(path, target, chunks=chunks, overwrite=args.overwrite, parts=args.parts, resume=args.resume,
                   dtype=args.dtype, compression=args.compression, nonfinite=args.nonfinite,
                   allow_read=args.allow_read, check_target=not args.dry_run and out_dir_ready,
                   folder_made_later=not args.dry_run and not out_dir_ready)
        if args.scheduler == "processes" and run.format == "netcdf":
            # the HDF5 writer's handle and lock cannot be shared with other processes (dask fails
            # pickling the lock after computing); Zarr stores take writes from any process
            raise UsageError(f"--scheduler processes writes Zarr stores only, not {target}; use the "
                             "default threads for NetCDF, or -o OUT.zarr")
        runs.append((path, run))
    if args.dry_run:
        for path, run in runs:
            e, recipe = run.estimate(), run.recipe
            dims = " x ".join(f"{d}={n}" for d, n in e["dims"].items()) or "scalar"
            print(f"{path} -> {run.target}\n  scenario {recipe.scenario.name}: {dims} = {e['points']:,} points; "
                  f"variables: {', '.join(recipe.variables)}\n  output about {e['bytes'] / 1e6:,.1f} MB; "
                  f"chunks {e['chunks']}; estimated {e['seconds']:,.1f} s here (from {e['sample_points']:,} "
                  "points)")
        return 0
    # every dataset (lazy) before any work: the free space is checked against all outputs at once
    if args.space_check:
        check_space([run for _, run in runs])
    _keep_freed_memory()
    scheduler, client = _scheduler(args.scheduler)
    local = contextlib.ExitStack()
    if client is None:
        local.enter_context(_local_scheduler(scheduler))
        scheduler = None        # dask's configuration names it now
    # what is alive now (modules, the recipes) lives to the end: the garbage collector's passes
    # during the computation then skip it (large runs ~10 % faster, docs/bench/tuning.md)
    gc.freeze()
    try:
        if not args.output:
            try:
                args.out_dir.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise OutputError(f"--out-dir {args.out_dir}: {exc.strerror or exc}") from None
        # progress bars (dask's, the cluster's) only where someone watches: not into pipes and logs
        progress = not args.quiet and sys.stderr.isatty()
        for path, run in runs:
            started = time.perf_counter()
            ds, recipe, target = run.dataset, run.recipe, run.target
            if not args.quiet:
                dims = " x ".join(f"{d}={n}" for d, n in recipe.shape.items()) or "scalar"
                print(f"{path} -> {target}  [{recipe.scenario.name}: {dims}, "
                      f"{len(ds.data_vars)} variables]", file=sys.stderr)
            if args.verbose:
                print(f"  chunks: {dict(ds.chunks) or 'one block'}", file=sys.stderr)
            try:
                run.write(progress=progress, scheduler=scheduler, space_check=args.space_check)
            except Exception as exc:
                if client is None or not _cluster_failure(exc, client):
                    raise
                reason = " ".join(str(exc).split())[:200]
                raise OutputError(f"the dask scheduler {args.scheduler} was lost during the run "
                                  f"({type(exc).__name__}: {reason}); {target} was not written") from None
            if args.verbose:
                _said_written(target, time.perf_counter() - started)
            if args.plot:
                from .plot import quicklook

                png = quicklook(target, recipe)
                if not args.quiet:
                    print(f"  quick look: {png}", file=sys.stderr)
    finally:
        if client is not None:
            _close(client)
        local.close()
        gc.unfreeze()
    return 0


def _said_written(target: Path, seconds: float) -> None:
    """-v: the written file's size, the time it took and its content hash, on stderr."""
    from .output.formats import format_for
    from .output.hashing import ATTR

    size = sum(f.stat().st_size for f in target.rglob("*") if f.is_file()) if target.is_dir() else target.stat().st_size
    with format_for(target).read(target, raw=True) as ds:
        digest = ds.attrs.get(ATTR, "none")
    print(f"  wrote {size:,} bytes in {seconds:.2f} s; content sha256 {digest}", file=sys.stderr)


@contextlib.contextmanager
def _local_scheduler(name: str):
    """Run on the local scheduler ``name`` without dask.distributed: dask is given the scheduler's
    function (a scheduler given by name makes dask look for a distributed client first) and xarray's
    own look for one (`from dask.distributed import Client`, when it writes NetCDF) finds no module.
    Both would import dask.distributed whenever it is installed: 0.17 s of a small run here. Both
    are restored on exit."""
    import dask
    import dask.local
    import dask.threaded

    functions = {"threads": dask.threaded.get, "synchronous": dask.local.get_sync}
    if name == "processes":
        import dask.multiprocessing

        functions[name] = dask.multiprocessing.get
    blocked = "distributed" not in sys.modules and "dask.distributed" not in sys.modules
    with dask.config.set(scheduler=functions[name]):
        if blocked:
            sys.modules["dask.distributed"] = None       # import fails: no client can exist here
        try:
            yield
        finally:
            if blocked and sys.modules.get("dask.distributed", 0) is None:
                del sys.modules["dask.distributed"]


def _check_plotting() -> None:
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise UsageError("--plot needs matplotlib: pip install 'stressfields[plot]'") from None


def _check_out_dir(out_dir: Path, flag: str = "--out-dir") -> bool:
    """Whether the output directory exists (then each target is checked in it); if it does not, that
    it can be created: its nearest existing ancestor is a writable directory. Nothing is created here."""
    if out_dir.is_dir():
        return True
    if os.path.lexists(out_dir):
        raise UsageError(f"{flag} {out_dir} is not a directory")
    ancestor = _existing_ancestor(out_dir)
    if not ancestor.is_dir():
        raise UsageError(f"{flag} {out_dir}: {ancestor} is not a directory")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise UsageError(f"{flag} {out_dir}: cannot create it, {ancestor} is not writable "
                         "(read-only or no permission)")
    return False


def _existing_ancestor(path: Path) -> Path:
    path = Path(os.path.abspath(path))
    while not os.path.lexists(path) and path != path.parent:
        path = path.parent
    return path


def _cluster_failure(exc: Exception, client) -> bool:
    """A lost scheduler or connection, as opposed to an error of the computation itself."""
    from concurrent.futures import CancelledError

    return (isinstance(exc, (OSError, CancelledError, TimeoutError)) or type(exc).__module__.startswith("distributed")
            or getattr(client, "status", "running") != "running")


def _close(client) -> None:
    try:
        client.close(timeout=5)
    except Exception:       # a scheduler that died is already gone: nothing to release
        pass


def _scheduler(name: str):
    if name in LOCAL_SCHEDULERS:
        return name, None
    try:
        from distributed import Client
    except ImportError:
        raise UsageError(f"--scheduler {name}: a cluster address needs dask.distributed "
                         "(pip install 'stressfields[cluster]')") from None
    from distributed.client import _del_global_client, _get_global_client

    before = _get_global_client()
    try:
        client = Client(name, timeout="10s")
        # a lost scheduler is reported in one line by `_run`; distributed's own log of the reconnection
        # attempts would add a traceback of some 40 lines
        for logger in ["distributed", *(n for n in logging.root.manager.loggerDict if n.startswith("distributed."))]:
            logging.getLogger(logger).setLevel(logging.CRITICAL)
    except Exception as exc:       # refused, timed out, or something that is not a dask scheduler
        # a half-made client stays the process-wide default and every later computation would go to it
        stuck = _get_global_client()
        if stuck is not None and stuck is not before:
            _del_global_client(stuck)
            _close(stuck)
        raise UsageError(f"--scheduler {name}: cannot connect ({type(exc).__name__}: {str(exc)[:200]})") from None
    return client, client


def _parse_chunks(text: str) -> dict[str, int]:
    chunks = {}
    for item in filter(None, (s.strip() for s in text.split(","))):
        dim, _, size = item.partition("=")
        try:
            value = int(size)
        except ValueError:
            raise UsageError(f"--chunks: {item!r} must look like dim=size with an integer size") from None
        if value < 1 and value != -1:
            raise UsageError(f"--chunks: {item!r}: size must be a positive integer or -1 (whole)")
        chunks[dim.strip()] = value
    return chunks


def _json(value) -> None:
    import json

    print(json.dumps(value, indent=2, ensure_ascii=False))


def _list(args) -> int:
    from .api import scenarios

    if args.json:
        _json(scenarios())
        return 0
    for name, summary in scenarios().items():
        print(f"{name:16s} {summary}")
    return 0


def _describe(args) -> int:
    from .api import describe

    try:
        text = describe(args.scenario)
    except KeyError as exc:
        raise UsageError(exc.args[0]) from None
    if args.json:
        from .scenarios import REGISTRY
        from .schema import scenario_record

        _json(scenario_record(REGISTRY[args.scenario]))
        return 0
    print(text)
    return 0


def _validate(args) -> int:
    from .recipe import load

    if sum(str(p) == "-" for p in args.recipes) > 1:
        raise UsageError("- (standard input) can be given once")
    failed, records = 0, []
    for path in args.recipes:
        try:
            recipe = load(path, allow_read=args.allow_read)
        except RecipeError as exc:
            failed += 1
            records.append({"recipe": str(path), "ok": False, "problems": exc.problems})
            if not args.json:
                print(str(exc), file=sys.stderr)
            continue
        records.append({"recipe": str(path), "ok": True, "scenario": recipe.scenario.name, "dims": recipe.shape,
                        "points": recipe.size, "variables": list(recipe.variables),
                        "recipe_sha256": recipe.sha256})
        if not args.json:
            dims = ", ".join(f"{d}={n}" for d, n in recipe.shape.items()) or "no swept dimension"
            print(f"{path}: ok ({recipe.scenario.name}; {dims}; {recipe.size} points; "
                  f"variables: {', '.join(recipe.variables)})")
    if args.json:
        _json(records)
    return 2 if failed else 0


def _example(args) -> int:
    from .api import example, examples

    if args.name is None:
        print("\n".join(examples()))
        return 0
    try:
        sys.stdout.write(example(args.name).read_text(encoding="utf-8"))
    except KeyError as exc:
        raise UsageError(exc.args[0]) from None
    return 0


def _schema(args) -> int:
    from .schema import document

    sys.stdout.write(document())
    return 0


if __name__ == "__main__":
    sys.exit(main())
