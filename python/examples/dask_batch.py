#!/usr/bin/env python3
"""uniparam over a batch of curves with Dask distributed.

Each task reparameterizes one curve (the radical method, 20 digits) and
returns its result document (plain dicts and strings: cheap to ship between
processes and machines). The results are the same, string for string, as a
serial loop's: every certified computation is deterministic, whatever the
worker, thread or machine.

    python3 dask_batch.py                        # a LocalCluster on this machine
    python3 dask_batch.py --workers 4            # 4 worker processes
    python3 dask_batch.py --scheduler tcp://HOST:8786   # a running cluster

On a real cluster: start a scheduler (``dask-scheduler``) on one machine and
workers (``dask-worker tcp://HOST:8786 --nthreads 1``) on the others, each
with uniparam installed (docs/python.md); then pass --scheduler. Give each
worker one thread per core (--nthreads) and let uniparam use one thread per
task (threads=1 below), or fewer Dask threads and more uniparam threads for a
few long curves.
"""

import argparse
import json

import uniparam as up

CURVES = [
    "(t, t^3)",
    "(t^2, t^3)",
    "(t, t^2, t^3)",
    "((1-t^2)/(1+t^2), 2*t/(1+t^2))",
    "(t, t^5 - t)",
    "(t^3 - t, t^2)",
    "(2*t/(1+t^2), t^3)",
    "(t + t^2, t^4 - t)",
]


def reparameterize(curve, digits=20):
    """One task: the radical reparameterization's document (docs/cli.md keys).
    threads=1: Dask already runs one task per worker thread."""
    return up.radical(curve, digits=digits, threads=1).json


def run(client, curves, digits=20):
    """The documents of all curves, in order, computed on the client's cluster."""
    futures = client.map(reparameterize, curves, digits=digits, pure=False)
    return client.gather(futures)


def serial(curves, digits=20):
    return [reparameterize(c, digits) for c in curves]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    ap.add_argument("--digits", type=int, default=20)
    ap.add_argument("--check", action="store_true", help="also compute serially and compare")
    args = ap.parse_args()

    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        client, cluster = Client(args.scheduler), None
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        docs = run(client, CURVES, args.digits)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    for doc in docs:
        print("%-36s pieces %2d   u %s -> %s" % (doc["curve"], len(doc["pieces"]), doc["u_before"]["mid"][:8],
                                                   doc["u_after"]["mid"][:8]))
    if args.check:
        same = json.dumps(docs) == json.dumps(serial(CURVES, args.digits))
        print("identical to the serial results:", same)
        return 0 if same else 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
