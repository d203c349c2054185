"""uniparam mapped over curves with Dask distributed (python/examples/
dask_batch.py) gives the serial results, string for string."""

import importlib.util
import json
import os

import pytest

distributed = pytest.importorskip("distributed", reason="Dask distributed is not installed (python3-distributed)")

import uniparam as up  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def load_example():
    path = os.path.join(HERE, "..", "examples", "dask_batch.py")
    spec = importlib.util.spec_from_file_location("dask_batch", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_local_cluster_threads_match_serial():
    ex = load_example()
    curves = ex.CURVES[:6]
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        docs = ex.run(client, curves, digits=20)
    assert json.dumps(docs) == json.dumps(ex.serial(curves, digits=20))


def test_local_cluster_processes_ship_curves():
    # Curve objects (Bezier ones too) are pickled to worker processes; the
    # Result documents come back
    curves = [up.Curve("(t, t^3)"), up.Curve.bezier([[0, 0], [0, 1], [3, 1]], weights=[1, 2, 1])]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        futures = client.map(up.uniformity, curves, speed="parametric", pure=False)
        results = client.gather(futures)
    for c, r in zip(curves, results):
        assert isinstance(r, up.Result) and isinstance(r.mu, up.Ball)
        assert json.dumps(r.json) == json.dumps(up.uniformity(c, speed="parametric").json)
