"""Run the benchmark: ``python benchmarks/run.py [--quick] [--peers] [-d DIR]`` (the same as
``stressfields bench`` from a clone)."""
import sys

from stressfields.cli import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:]]))
