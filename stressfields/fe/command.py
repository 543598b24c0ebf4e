"""`stressfields compare RECIPE FILE [FILE ...]`: the FE comparison of ``validate`` written as a report
folder (``report``), checked before anything is computed and published whole when complete."""
from __future__ import annotations

import math
import sys

from ..comparison import CompareError
from . import report
from .units import UnitProblem, parse_unit_option
from .validate import Options, compare_files, convergence, parse_tolerance


def options_from(args) -> Options:
    try:
        units = parse_unit_option(args.units)
    except UnitProblem as exc:
        raise CompareError(str(exc)) from None
    h = None
    if args.h:
        try:
            h = tuple(float(v) for v in args.h.split(","))
        except ValueError:
            h = (math.nan,)
        if not all(math.isfinite(v) and v > 0 for v in h):
            raise CompareError(f"--h {args.h}: comma-separated positive mesh sizes, one per file (e.g. 0.2,0.1,0.05)")
    if args.step is not None and args.step < 1:
        raise CompareError(f"--step {args.step}: a time step counts from 1")
    return Options(tolerance=parse_tolerance(args.tolerance), variables=tuple(args.variables or ()) or None,
                   step=args.step, units=units, z_up=args.z_up, axisymmetric=args.axisymmetric, body=args.body,
                   exclude_edge=args.exclude_edge, remove_rigid_offset=args.remove_rigid_offset, scale=args.scale,
                   h=h)


def run(args, plotting: bool) -> int:
    """The command: the report folder is checked before anything is computed and published whole
    (`comparison.publish_report`); ``plotting``: the PNGs are drawn (not --no-plot, and matplotlib is
    installed: cli.py decides)."""
    from ..comparison import check_report_folder, publish_report
    from ..textfiles import write_text
    from ..output.formats import write

    options = options_from(args)
    files = list(args.user_data)
    if options.h is not None and len(options.h) != len(files):
        raise CompareError(f"--h gives {len(options.h)} sizes for {len(files)} files")
    out = args.report_dir
    check_report_folder(out, overwrite=args.overwrite)
    if not plotting and not args.no_plot:
        print("note: no comparison.png: matplotlib is not installed (pip install 'stressfields[plot]')",
              file=sys.stderr)
    datasets = compare_files(args.recipe, files, options)
    conv = convergence(datasets, options.h) if len(files) > 1 else None

    def fill(tmp) -> None:
        for ds, name in zip(datasets, report.nc_names(len(datasets))):
            write(ds, tmp / name)
        if plotting:
            for ds, name in zip(datasets, report.png_names(len(datasets))):
                report.plot_table(ds, tmp / name)
            if conv is not None:
                report.plot_convergence(conv, tmp / "convergence.png")
            note = "Quick look: " + ", ".join(f"`{n}`" for n in report.png_names(len(datasets))) + \
                (", `convergence.png`" if conv else "") + " (depth downward, zoomed on the largest differences)."
        else:
            note = "No plot (" + ("--no-plot" if args.no_plot else "matplotlib is not installed") + ")."
        write_text(tmp / "report.md", report.report_markdown(datasets, str(args.recipe), conv, note))
        write_text(tmp / "report.json", report.report_json(datasets, str(args.recipe), conv))

    publish_report(out, fill, overwrite=args.overwrite)
    for ds in datasets:
        if len(datasets) > 1:
            print(ds.attrs["compare_user_data"])
        for name in ds.attrs["compare_variables"].split():
            a = {k[len(f"compare_{name}_"):]: v for k, v in ds.attrs.items() if k.startswith(f"compare_{name}_")}
            node = f"node {a['worst_node']}, " if "worst_node" in a else ""
            edge = (f"; edge ring {a['edge_compared_points']} points, max {a['edge_max_abs_difference_over_scale']:.3e}"
                    if "edge_compared_points" in a else "")
            print(f"{name:12s} max |diff|/scale {a['max_abs_difference_over_scale']:.3e} at point {a['worst_point']} "
                  f"({node}{a.get('worst_coordinates', '')}); RMS/scale {a['rms_difference_over_scale']:.3e}; "
                  f"p95 {a.get('p95_abs_difference_over_scale', math.nan):.3e}; relative L2 {a['relative_l2']:.3e}"
                  f"{edge}; {a['result']}" + (f" ({a['note']})" if "note" in a else ""))
    if conv is not None:
        for var, row in conv["variables"].items():
            if "rms" in row:
                print(f"{var:12s} observed RMS order {row['rms']['fitted_order']:.3f} "
                      f"(pairs {', '.join(f'{p:.3f}' for p in row['rms']['orders'])})")
    result = report.overall(datasets)
    print(f"{result}; report in {out}")
    sys.stdout.flush()
    return 1 if result == "FAIL" else 0

