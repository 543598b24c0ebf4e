"""A recipe on a dask.distributed cluster of separate processes writes a Zarr store from the
workers; killing a worker mid-run changes nothing in the result."""
import threading
import time

import pytest

from stressfields import cli
from stressfields.output.formats import file_hash

pytestmark = pytest.mark.slow   # kills cluster workers mid-write; run by .ci/run

distributed = pytest.importorskip("distributed")
pytest.importorskip("zarr")

RECIPE = """scenario = "axisymmetric"
[parameters]
n = 3.0
nu = [0.2, 0.3]
mu = [0.2, 0.4]
ux0 = 0.25
y = { start = -1.5, stop = 1.5, num = 60 }
x = { start = -1.5, stop = 1.5, num = 400 }
[output]
variables = ["sigma_xx", "von_mises", "dpdz"]
chunks = { y = 3 }
[method]
method = "quadrature"
"""


def test_zarr_on_a_cluster_survives_a_killed_worker(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE)
    local = tmp_path / "local.zarr"
    assert cli.main(["run", str(recipe), "-o", str(local), "-q"]) == 0

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        out = tmp_path / "cluster.zarr"
        result = {}
        run = threading.Thread(target=lambda: result.setdefault(
            "code", cli.main(["run", str(recipe), "-o", str(out), "-q", "--scheduler", cluster.scheduler_address])))
        run.start()
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and run.is_alive():
            # the store is built under a unique temporary name: .cluster.zarr.HOST-PID.RANDOM.partial
            partial = [p / "von_mises" for p in tmp_path.glob(".cluster.zarr.*.partial")]
            if partial and sum(1 for p in partial[0].rglob("*") if p.is_file()) > 6:
                break
            time.sleep(0.02)
        assert run.is_alive(), "the run finished before a worker could be killed"
        victim = next(iter(cluster.workers.values()))
        victim.process.process.kill()                # SIGKILL the worker process mid-run
        run.join(timeout=120)
        assert result.get("code") == 0
    digest, stored = file_hash(out)
    assert digest == stored == file_hash(local)[0]
    assert cli.main(["hash", str(out)]) == 0


def test_export_zarr_to_netcdf_equals_a_direct_netcdf_run(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text(RECIPE.replace("num = 400", "num = 40"))
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "a.zarr"), "-q"]) == 0
    assert cli.main(["export", str(tmp_path / "a.zarr"), "-o", str(tmp_path / "a.nc")]) == 0
    assert cli.main(["run", str(recipe), "-o", str(tmp_path / "b.nc"), "-q"]) == 0
    assert file_hash(tmp_path / "a.nc")[0] == file_hash(tmp_path / "b.nc")[0]
