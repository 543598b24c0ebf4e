"""A run killed at any moment leaves no file at the target and no part listed that is not on disk; --resume finishes
it and the content hash equals that of an uninterrupted run."""
import json

import netCDF4
import numpy as np
import pytest

from stressfields import cli
from stressfields.output.formats import file_hash
from conftest import kill_after_two_parts

RECIPE = """scenario = "conical"
[parameters]
nu = { start = 0.0, stop = 0.5, num = 12 }
mu = [0.2, 0.3, 0.4]
ux0 = 0.25
y = { start = -1.5, stop = 1.5, num = 101 }
x = { start = -1.5, stop = 1.5, num = 121 }
[output]
chunks = { nu = 1 }
"""


@pytest.mark.slow
def test_sigkill_then_resume(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    whole, target = tmp_path / "whole.nc", tmp_path / "out.nc"
    assert cli.main(["run", str(recipe), "-o", str(whole), "-q"]) == 0

    plan = kill_after_two_parts(recipe, target, timeout=60)

    assert not target.exists()
    done = plan["parts"]
    assert plan["laid_out"] and 2 <= len(done) < 12
    edges = plan["edges"]
    with netCDF4.Dataset(whole) as w, netCDF4.Dataset(tmp_path / "out.nc.parts" / "data.nc") as d:
        for i in map(int, done):         # every part the manifest lists is on disk, value for value
            rows = slice(edges[i], edges[i + 1])
            for name in ("sigma_xx", "von_mises", "validity"):
                np.testing.assert_array_equal(d[name][rows], w[name][rows])

    assert cli.main(["run", str(recipe), "-o", str(target), "-q"]) == 2        # refuses without --resume
    assert cli.main(["run", str(recipe), "-o", str(target), "-q", "--resume"]) == 0
    assert not (tmp_path / "out.nc.parts").exists()
    assert file_hash(target)[0] == file_hash(whole)[0] == file_hash(target)[1]


def test_resume_refuses_parts_of_another_recipe(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    (tmp_path / "out.nc.parts").mkdir()
    (tmp_path / "out.nc.parts" / "manifest.json").write_text(
        json.dumps({"recipe_sha256": "0" * 64, "dim": "nu", "edges": [0, 12], "parts": {}}))
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "out.nc"), "-q", "--resume"]) == 2
    assert not (tmp_path / "out.nc").exists()
