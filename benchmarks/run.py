"""Run the benchmark outside the installed CLI: ``python benchmarks/run.py [--quick] [--peers] [-d DIR]``.

The same as ``stressfields bench``; kept here because benchmarks live apart from the tests.
"""
import sys

from stressfields.cli import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:]]))
