"""Runs a study's rows on a Dask cluster and writes its table, byte for byte
what `tirecontact study run` (or `study merge` of its shards) writes.

    python examples/dask_study.py examples/study.ron results.csv [--workers 2]
    python examples/dask_study.py STUDY OUT --scheduler tcp://host:8786

Each worker loads the study once (a ring tyre identified once per worker
process) and runs the rows it is given; `tirecontact.run_row` releases the
GIL, so a worker's threads run rows in parallel. Rows go to the workers in
batches (about eight batches per worker thread): a row of a short study
takes a few milliseconds, about Dask's own cost per task.
"""

import argparse
import functools
import sys
import time

import pandas as pd
from dask.distributed import Client, LocalCluster

import tirecontact as tc


@functools.lru_cache(maxsize=4)
def _study(path):
    return tc.Study.load(path)


def run_rows(path, row_ids):
    """The records of a batch of rows, on whichever worker runs it."""
    study = _study(path)
    return [tc.run_row(study, row) for row in row_ids]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study", help="study file (RON)")
    ap.add_argument("output", help="results table (CSV)")
    ap.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    ap.add_argument("--scheduler", help="address of an existing Dask scheduler instead")
    ap.add_argument(
        "--rows-per-task",
        type=int,
        help="rows in a Dask task (default: about eight tasks per worker thread)",
    )
    a = ap.parse_args(argv)
    if a.rows_per_task is not None and a.rows_per_task < 1:
        ap.error(f"--rows-per-task = {a.rows_per_task}: expected 1 or more rows")
    study = tc.Study.load(a.study)
    ids = [row for row, _, _ in tc.study_rows(study)]
    start = time.time()
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True)
        client = Client(cluster)
    try:
        threads = sum(client.nthreads().values()) or 1
        per_task = a.rows_per_task or max(1, len(ids) // (8 * threads))
        batches = [ids[i : i + per_task] for i in range(0, len(ids), per_task)]
        futures = client.map(run_rows, [a.study] * len(batches), batches, pure=False)
        records = [r for batch in client.gather(futures) for r in batch]
    finally:
        client.close()
        if not a.scheduler:
            cluster.close()
    study.write_table(a.output, records)
    failed = sum(1 for r in records if r[-1])
    table = pd.read_csv(a.output)
    print(
        f"wrote {a.output} ({len(records)} rows on "
        f"{'the cluster at ' + a.scheduler if a.scheduler else str(a.workers) + (' worker' if a.workers == 1 else ' workers')} "
        f"in {len(batches)} tasks, {time.time() - start:.1f} s, {failed} failed; {table.shape[1]} columns)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
