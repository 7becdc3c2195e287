"""Parameter sweeps on dask.distributed: `python -m powderfmu.sweep SPEC.json`.

A spec is a JSON object:

    {
      "task": "sieve",                        # or "indentation" (BallIndentation), "compression" (UnconfinedCompression)
      "base": {"particles": 20},              # keys every task shares (system keys or unit parameters)
      "grid": {"frequency": [1e3, 1e4], "acceleration": [1e5, 1e6]},   # every combination, or
      "sample": {"count": 50, "seed": 1, "ranges": {"frequency": [1e3, 1e6, "log"]}},
      "output": "out/sweep.csv"               # optional; --output wins
    }

Each task is one run of the system (or one indentation test); the FMU instances live inside the worker
that runs it. Results stream to one CSV file, a row per task as it finishes, after comment lines that
hold the spec and the versions. A failed task is retried once, then written with its error and reported
with its inputs. A run that was interrupted resumes: the tasks already in the file are not run again
(failed ones are). The whole spec is checked before any task starts.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import itertools
import json
import math
import os
import platform
import importlib
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

import numpy as np

from . import __version__
from .fmus import fmu_path

@dataclass(frozen=True)
class Task:
    """A kind of task a sweep can run: the unit it drives and the module that runs it. The module gives
    `resolve(inputs, check_unit=True)` (every input checked, nothing run), `run(inputs)` (the summary row,
    a mapping, or an object with `summary()`) and `SUMMARY_KEYS` (the row's columns in order)."""

    unit: str
    module: str

    def code(self):
        return importlib.import_module(f".{self.module}", __package__)

    def resolve(self, inputs: Mapping[str, Any]) -> None:
        self.code().resolve(inputs, check_unit=True)

    def run(self, inputs: Mapping[str, Any]) -> dict[str, Any]:
        out = self.code().run(inputs)
        return out.summary() if hasattr(out, "summary") else out

    def summary_keys(self) -> tuple[str, ...]:
        return self.code().SUMMARY_KEYS


#: The tasks by the name a spec's `task` gives; a new kind of task is one line here and its module.
TASKS: dict[str, Task] = {
    "sieve": Task(unit="ParticleWallImpact", module="sieve"),
    "indentation": Task(unit="BallIndentation", module="indentation"),
    "compression": Task(unit="UnconfinedCompression", module="compression"),
}


class SweepError(ValueError):
    """A spec that cannot run, or an output file of another sweep; the message says which key."""


# ---------------------------------------------------------------------------------------------------
# The spec


def load_spec(path: str | Path) -> dict[str, Any]:
    from .scene import read_object

    return read_object(path, "task, base, grid or sample, output", SweepError)


def points(spec: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The varied keys of every task, in a fixed order: the grid's combinations, or the sample's draws."""
    known = {"task", "base", "grid", "sample", "output"}
    extra = [k for k in spec if k not in known and not k.startswith("comment")]
    if extra:
        raise SweepError(f"unknown spec key(s) {', '.join(map(repr, extra))}: a spec has {', '.join(sorted(known))}")
    if ("grid" in spec) == ("sample" in spec):
        raise SweepError("a spec needs exactly one of `grid` (lists of values per key) and `sample` (count, seed, ranges)")
    if "grid" in spec:
        grid = spec["grid"]
        if not isinstance(grid, dict) or not grid:
            raise SweepError("`grid` is empty: give at least one key with a list of values")
        for key, values in grid.items():
            if not isinstance(values, list) or not values:
                raise SweepError(f"`grid.{key}` must be a non-empty list of values")
        keys = list(grid)
        for key in keys:
            seen = set()
            for value in grid[key]:
                marker = json.dumps(value, sort_keys=True)
                if marker in seen:
                    raise SweepError(f"`grid.{key}` lists {value!r} twice: every task must be different")
                seen.add(marker)
        return [dict(zip(keys, combo)) for combo in itertools.product(*(grid[k] for k in keys))]
    sample = spec["sample"]
    if not isinstance(sample, dict):
        raise SweepError("`sample` must be an object: count, seed, ranges")
    count, seed, ranges = sample.get("count"), sample.get("seed", 0), sample.get("ranges")
    if not isinstance(count, int) or isinstance(count, bool) or count < 1:
        raise SweepError(f"`sample.count` = {count!r} must be an integer >= 1")
    if not isinstance(ranges, dict) or not ranges:
        raise SweepError("`sample.ranges` is empty: give at least one key with [low, high] or [low, high, \"log\"]")
    rng = np.random.default_rng(seed)
    draws = {}
    for key, r in ranges.items():
        if not (isinstance(r, list) and len(r) in (2, 3) and all(isinstance(x, (int, float)) for x in r[:2]) and (len(r) == 2 or r[2] in ("lin", "log"))):
            raise SweepError(f"`sample.ranges.{key}` = {r!r} must be [low, high] or [low, high, \"lin\"|\"log\"]")
        low, high = float(r[0]), float(r[1])
        if not low < high:
            raise SweepError(f"`sample.ranges.{key}`: low {low} must be below high {high}")
        u = rng.random(count)
        if len(r) == 3 and r[2] == "log":
            if low <= 0:
                raise SweepError(f"`sample.ranges.{key}`: a log range needs low > 0, not {low}")
            draws[key] = np.exp(np.log(low) + u * (np.log(high) - np.log(low)))
        else:
            draws[key] = low + u * (high - low)
    return [{k: float(draws[k][i]) for k in ranges} for i in range(count)]


def task_id(point: Mapping[str, Any]) -> str:
    """A short, stable name of a task's inputs (resume matches on it)."""
    return hashlib.sha256(json.dumps(point, sort_keys=True).encode()).hexdigest()[:16]


def check(spec: Mapping[str, Any]) -> tuple[str, dict[str, Any], list[dict[str, Any]]]:
    """The task kind, base keys and points of a spec, every task's inputs checked before anything runs."""
    task = spec.get("task", "sieve")
    if task not in TASKS:
        raise SweepError(f"`task` = {task!r} is not one of {', '.join(TASKS)}")
    base = spec.get("base", {})
    if not isinstance(base, dict):
        raise SweepError("`base` must be an object of keys shared by every task")
    pts = points(spec)
    for p in pts:
        try:
            resolve_task(task, {**base, **p})
        except (ValueError, RuntimeError) as e:  # a bad key or value; no FMU to run
            raise SweepError(f"task {p}: {e}") from None
    return task, base, pts


def resolve_task(task: str, inputs: Mapping[str, Any]) -> None:
    TASKS[task].resolve(inputs)


# ---------------------------------------------------------------------------------------------------
# One task (runs in a worker)


def run_task(task: str, inputs: Mapping[str, Any]) -> dict[str, Any]:
    """One system run (or indentation test): its summary row. Deterministic: the same inputs give the
    same numbers on any worker."""
    return TASKS[task].run(inputs)


# ---------------------------------------------------------------------------------------------------
# The output file


def versions() -> dict[str, str]:
    import fmpy

    out = {"powderfmu": __version__, "python": platform.python_version(), "numpy": np.__version__, "fmpy": fmpy.__version__}
    try:
        import dask
        import distributed

        out["dask"], out["distributed"] = dask.__version__, distributed.__version__
    except ImportError:
        pass
    return out


def _rows(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    """The comment lines and the complete rows of an output file, the last row of each task (a task
    that failed and then ran again keeps its last outcome; a line torn by an interruption is dropped)."""
    with path.open(newline="") as f:
        text = f.read()
    comments = [line for line in text.split("\n") if line.startswith("#")]
    body = [line for line in text.split("\n") if line and not line.startswith("#")]
    if not body:
        return comments, []
    records = list(csv.reader(body))
    header, latest = records[0], {}
    for rec in records[1:]:
        if len(rec) == len(header) and rec[-2] in ("ok", "failed"):
            row = dict(zip(header, rec))
            latest[row["task_id"]] = row
    return comments, list(latest.values())


def _read_done(path: Path, spec_text: str, fmu_text: str) -> tuple[dict[str, dict[str, str]], list[str] | None]:
    """The finished rows of an earlier run of the same spec with the same FMU (by task id) and its columns;
    an error for another sweep's file."""
    if not path.exists():
        return {}, None
    comments, rows = _rows(path)
    meta = [line for line in comments if line.startswith("# spec: ")]
    if not meta or meta[0][len("# spec: ") :] != spec_text:
        raise SweepError(f"{path} holds the results of another sweep (its spec differs); give another --output or --restart")
    fmu = [line for line in comments if line.startswith("# fmu: ")]
    if fmu and fmu[0][len("# fmu: ") :] != fmu_text:
        raise SweepError(f"{path} was written with another build of the FMU ({fmu[0][len('# fmu: '):]}, now {fmu_text}); give another --output or --restart")
    header = next((line for line in path.read_text().splitlines() if line and not line.startswith("#")), None)
    return {r["task_id"]: r for r in rows if r["status"] == "ok"}, (header.split(",") if header else None)


def _has_header(path: Path) -> bool:
    return path.exists() and any(not line.startswith("#") for line in path.read_text().splitlines())


def _summary_keys(task: str) -> tuple[str, ...]:
    return TASKS[task].summary_keys()


def _fmu_identity(task: str) -> str:
    from fmpy import read_model_description

    path = fmu_path(TASKS[task].unit)
    return f"{path.name} guid {read_model_description(str(path)).guid}"


def _fmt(x: Any) -> str:
    if isinstance(x, float):
        return repr(x)  # every bit: a sweep's numbers are compared bit for bit
    if isinstance(x, (np.floating,)):
        return repr(float(x))
    return str(x)


# ---------------------------------------------------------------------------------------------------
# Running


class Progress:
    def __init__(self, total: int, done: int, enabled: bool):
        self.total, self.done, self.failed, self.enabled = total, done, 0, enabled
        self.start, self.started_with = time.perf_counter(), done

    def tick(self, failed: bool = False) -> None:
        self.done += 1
        self.failed += failed
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        ran = self.done - self.started_with
        left = elapsed / ran * (self.total - self.done) if ran else math.nan
        bar = "#" * int(30 * self.done / self.total)
        print(
            f"\r  [{bar:<30}] {self.done}/{self.total} tasks  {self.failed} failed  elapsed {elapsed:6.1f} s  left ~{left:6.1f} s",
            end="" if self.done < self.total else "\n",
            file=sys.stderr,
            flush=True,
        )


def run(
    spec: Mapping[str, Any],
    output: str | Path,
    workers: int = 2,
    scheduler: str | None = None,
    serial: bool = False,
    restart: bool = False,
    progress: bool = True,
    task_runner: Callable[[str, Mapping[str, Any]], dict[str, Any]] = run_task,
) -> dict[str, Any]:
    """Runs a sweep; returns counts {tasks, skipped, ran, failed, output, wall_time}. `serial` runs the
    tasks in this process, one after the other, without Dask."""
    task, base, pts = check(spec)
    output = Path(output)
    spec_text = json.dumps(spec, sort_keys=True)
    if restart and output.exists():
        output.unlink()
    fmu_text = _fmu_identity(task)
    done, columns = _read_done(output, spec_text, fmu_text)
    if output.exists() and not output.read_bytes().endswith(b"\n"):
        # A run killed in the middle of a row: end the torn line (it is not `ok`, so its task runs again).
        with output.open("a") as f:
            f.write("\n")
    todo = [p for p in pts if task_id(p) not in done]
    counts = {"tasks": len(pts), "skipped": len(pts) - len(todo), "ran": 0, "failed": 0, "output": str(output)}
    output.parent.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    if not output.exists():
        with output.open("w") as f:
            f.write("# powderfmu sweep\n")
            f.write(f"# spec: {spec_text}\n")
            f.write(f"# versions: {json.dumps(versions(), sort_keys=True)}\n")
            f.write(f"# fmu: {fmu_text}\n")
    varied = list(pts[0]) if pts else []
    if columns is None:
        columns = ["task_id", *varied, *(k for k in _summary_keys(task) if k not in varied), "status", "error"]
    bar = Progress(len(pts), counts["skipped"], progress)
    failures: list[str] = []
    writer_state = {"columns": columns, "header_written": _has_header(output)}

    def write(point: Mapping[str, Any], row: Mapping[str, Any] | None, error: str | None) -> None:
        record = {"task_id": task_id(point), **{k: point[k] for k in varied}}
        if row is not None:
            record.update({k: v for k, v in row.items() if k not in record})
        record["status"] = "ok" if error is None else "failed"
        record["error"] = "" if error is None else error.replace("\n", " ")
        with output.open("a", newline="") as f:
            if not writer_state["header_written"]:
                f.write(",".join(writer_state["columns"]) + "\n")
                writer_state["header_written"] = True
            w = csv.DictWriter(f, fieldnames=writer_state["columns"], extrasaction="ignore", restval="", lineterminator="\n")
            w.writerow({k: _fmt(v) for k, v in record.items()})
        counts["ran" if error is None else "failed"] += 1
        if error is not None:
            failures.append(f"task {task_id(point)} {json.dumps(point)} failed twice: {error}")
        bar.tick(error is not None)

    if serial:
        for p in todo:
            inputs = {**base, **p}
            error, row = None, None
            for _attempt in range(2):
                try:
                    row, error = task_runner(task, inputs), None
                    break
                except Exception as e:  # noqa: BLE001 - a task's failure is reported, the sweep goes on
                    error = f"{type(e).__name__}: {e}"
            write(p, row, error)
    elif todo:
        from distributed import Client, LocalCluster, as_completed

        cluster = None
        if scheduler:
            client = Client(scheduler)
        else:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
            client = Client(cluster)
        try:
            futures = {client.submit(task_runner, task, {**base, **p_}, key=f"task-{task_id(p_)}", retries=1, pure=False): p_ for p_ in todo}
            for fut in as_completed(futures):
                p = futures[fut]
                try:
                    write(p, fut.result(), None)
                except Exception as e:  # noqa: BLE001 - reported with the task's inputs
                    write(p, None, f"{type(e).__name__}: {e}")
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    for line in failures:
        print(line, file=sys.stderr)
    counts["wall_time"] = time.perf_counter() - started
    return counts


def read(output: str | Path) -> tuple[dict[str, Any], list[dict[str, str]]]:
    """The spec and the rows of a sweep's output file (the last complete row of each task)."""
    comments, rows = _rows(Path(output))
    spec = json.loads(next(line for line in comments if line.startswith("# spec: "))[len("# spec: ") :])
    return spec, rows


def main(argv: Iterable[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m powderfmu.sweep", description=__doc__.split("\n\n")[0])
    ap.add_argument("spec", help="the sweep spec (JSON: task, base, grid or sample, output)")
    ap.add_argument("--output", help="the CSV file of results (default: the spec's `output`, else SPEC.csv)")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="workers of the LocalCluster (default: the cores)")
    ap.add_argument("--scheduler", help="address of an existing dask scheduler (tcp://host:8786) instead of a LocalCluster")
    ap.add_argument("--serial", action="store_true", help="run the tasks in this process, one after the other, without Dask")
    ap.add_argument("--restart", action="store_true", help="discard the results already in the output file")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(list(argv) if argv is not None else None)
    if args.workers < 1:
        ap.error(f"--workers {args.workers}: allowed >= 1")
    output = args.output or "the output file"
    try:
        spec = load_spec(args.spec)
        output = args.output or spec.get("output") or str(Path(args.spec).with_suffix(".csv"))
        counts = run(spec, output, workers=args.workers, scheduler=args.scheduler, serial=args.serial, restart=args.restart, progress=not args.quiet)
    except SweepError as e:
        print(f"powderfmu.sweep: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"\npowderfmu.sweep: interrupted; the finished tasks are in {output}: run the same command again to resume", file=sys.stderr)
        return 130
    print(
        f"{counts['tasks']} tasks: {counts['ran']} ran, {counts['skipped']} already done, {counts['failed']} failed; "
        f"{counts['wall_time']:.1f} s; results in {counts['output']}"
    )
    return 1 if counts["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
