"""touchdown from Python: Monte Carlo touchdowns of legged landers on asteroids.

The same library as the ``touchdown`` command line, called in process::

    import touchdown, polars as pl

    s = touchdown.Scenario.default()
    s["surface.friction_coefficient"] = 0.4
    table = touchdown.sweep(s, samples=100_000, seed=7)     # a pyarrow.Table
    df = pl.from_arrow(table)
    print(touchdown.trace(s, sample=3))                      # one sample in full
    touchdown.report(table)["outcomes"]["stable"]["share"]

A sweep comes back as a ``pyarrow.Table`` through the Arrow C stream interface (no copy),
with the schema metadata its file would have (``touchdown.scenario``, ``touchdown.seed``,
...), equal column for column to the file ``touchdown sweep`` writes with the same
scenario, seed and samples. A control law can be a Python class (``register_law``).
Errors keep the command line's messages: a scenario refused raises ``ScenarioError``, a
sweep stopped by Ctrl-C raises ``KeyboardInterrupt`` and leaves no file that looks
complete.
"""

from __future__ import annotations

import contextlib
import dataclasses
import importlib.util
import json
import os
import re
import sys
import tempfile
from pathlib import Path
from typing import Any, Dict, Iterator, Literal, Optional, Union, overload

import pyarrow as pa

from . import _touchdown
from ._touchdown import (
    ENGINE,
    Scenario,
    ScenarioError,
    Sensed,
    TouchdownError,
    register_law,
    registered_laws,
)

#: The package's version: the engine's (``ENGINE`` is "touchdown VERSION", as files record).
__version__ = ENGINE.split()[-1]

__all__ = [
    "ENGINE",
    "Command",
    "Scenario",
    "ScenarioError",
    "Sensed",
    "Trace",
    "TouchdownError",
    "register_law",
    "registered_laws",
    "report",
    "report_markdown",
    "sweep",
    "trace",
]

PathLike = Union[str, "os.PathLike[str]"]
#: A whole number as the command line takes one: an int, a float that is whole (``1e5``)
#: or a string (``"1e5"``, ``"2.5e5"``, ``"1_000"``).
Whole = Union[int, float, str]


@dataclasses.dataclass
class Command:
    """What a control law commands for the landers of a call, as ``command`` returns it.

    Each field may be left ``None`` (nothing commanded) or given for all landers at once
    (one row broadcast to every lander).

    Attributes:
        force_b_n: Force in the body frame B, N, shape (n, 3): a mean over the control
            period, shared among the thrusters by the control loop's allocation.
        torque_b_n_m: Torque about the CG in B, N m, shape (n, 3).
        done: The law commands nothing more for the lander, shape (n,): once its last
            firing is over, the lander is left to itself.
    """

    force_b_n: Any = None
    torque_b_n_m: Any = None
    done: Any = None


def _scenario_text(scenario: Union[None, Scenario, PathLike]) -> str:
    """The TOML text of a scenario given as a ``Scenario``, a file's path or None."""
    if scenario is None:
        return _touchdown.DEFAULT_TOML
    if isinstance(scenario, Scenario):
        return scenario.to_toml()
    if isinstance(scenario, (str, os.PathLike)):
        return Scenario.load(scenario).to_toml()
    raise TypeError(
        f"scenario: expected a touchdown.Scenario, a path to a scenario file or None, "
        f"not {type(scenario).__name__}"
    )


def _as_arrow(table: Any) -> pa.Table:
    """Any table pyarrow can take (polars, pandas, pyarrow, an Arrow C stream) as one."""
    if isinstance(table, pa.Table):
        return table
    if type(table).__module__.split(".")[0] == "pandas":
        return pa.Table.from_pandas(table, preserve_index=False)
    if hasattr(table, "__arrow_c_stream__"):
        return pa.table(table)
    if hasattr(table, "to_arrow"):
        return table.to_arrow()
    raise TypeError(
        f"inputs: a {type(table).__name__} is not a table (give a path, or a pyarrow, "
        f"polars or pandas table)"
    )


#: What messages call a table of inputs held in memory (not the temporary file it is
#: written to for the run, which is gone when the message is read).
_GIVEN_TABLE = "inputs (the table given)"

#: A sweep's table of inputs that was held in memory, as the library names it when it is
#: not there (the temporary file it was written to is gone with the sweep's run).
_GONE_TABLE = re.compile(
    r"the table of inputs \S*touchdown-inputs-[^/\\]+[/\\]inputs\.arrow, which is not there: "
    r"give it with --inputs"
)
_GONE_TABLE_SAYS = "a table of inputs held in memory: give trace inputs= that table again"


@contextlib.contextmanager
def _inputs_path(inputs: Any) -> Iterator[Optional[str]]:
    """The path of a table of inputs: a path as it is; a table in memory written as an
    Arrow IPC file into a private temporary folder, removed when the run is over. An
    exception that names that file names the table given instead."""
    if inputs is None:
        yield None
        return
    if isinstance(inputs, (str, os.PathLike)):
        yield os.fspath(inputs)
        return
    table = _as_arrow(inputs)
    with tempfile.TemporaryDirectory(prefix="touchdown-inputs-") as folder:
        path = os.path.join(folder, "inputs.arrow")
        with pa.OSFile(path, "wb") as sink, pa.ipc.new_file(sink, table.schema) as writer:
            writer.write_table(table)
        try:
            yield path
        except BaseException as e:
            e.args = tuple(
                a.replace(f"--inputs {path}", _GIVEN_TABLE).replace(path, _GIVEN_TABLE)
                if isinstance(a, str)
                else a
                for a in e.args
            )
            raise


class _Bar:
    """A progress bar: tqdm's (a terminal's or Jupyter's) where tqdm is installed, else a
    line on a terminal's stderr, else nothing."""

    def __init__(self, total: int, show: Optional[bool]) -> None:
        self.done = 0
        self.bar = None
        self.line = False
        in_jupyter = "ipykernel" in sys.modules
        if show is None:
            show = in_jupyter or sys.stderr.isatty()
        if not show:
            return
        try:
            # Jupyter's widget where ipywidgets can draw it, else the text bar (in a
            # notebook too: tqdm.auto without ipywidgets only warns and falls back).
            if in_jupyter and importlib.util.find_spec("ipywidgets") is not None:
                from tqdm.auto import tqdm
            else:
                from tqdm import tqdm
        except ImportError:
            self.line = sys.stderr.isatty()
            self.total = total
            return
        self.bar = tqdm(total=total, unit=" samples", unit_scale=True, desc="touchdown sweep")

    def update(self, done: int) -> None:
        if done <= self.done:
            return
        if self.bar is not None:
            self.bar.update(done - self.done)
        elif self.line:
            sys.stderr.write(f"\r{done}/{self.total} samples")
            sys.stderr.flush()
        self.done = done

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.line:
            sys.stderr.write("\n")


# A pyarrow.Table where table= is left True (type checkers know it), else None or one.
@overload
def sweep(
    scenario: Union[None, Scenario, PathLike] = None,
    *,
    samples: Optional[Whole] = None,
    seed: Optional[Whole] = None,
    threads: Optional[Whole] = None,
    design: Optional[str] = None,
    inputs: Any = None,
    keep_columns: bool = False,
    out: Optional[PathLike] = None,
    format: Optional[str] = None,
    kernel: str = "auto",
    progress: Optional[bool] = None,
    table: Literal[True] = ...,
) -> pa.Table: ...
@overload
def sweep(
    scenario: Union[None, Scenario, PathLike] = None,
    *,
    samples: Optional[Whole] = None,
    seed: Optional[Whole] = None,
    threads: Optional[Whole] = None,
    design: Optional[str] = None,
    inputs: Any = None,
    keep_columns: bool = False,
    out: Optional[PathLike] = None,
    format: Optional[str] = None,
    kernel: str = "auto",
    progress: Optional[bool] = None,
    table: bool = ...,
) -> Optional[pa.Table]: ...
def sweep(
    scenario: Union[None, Scenario, PathLike] = None,
    *,
    samples: Optional[Whole] = None,
    seed: Optional[Whole] = None,
    threads: Optional[Whole] = None,
    design: Optional[str] = None,
    inputs: Any = None,
    keep_columns: bool = False,
    out: Optional[PathLike] = None,
    format: Optional[str] = None,
    kernel: str = "auto",
    progress: Optional[bool] = None,
    table: bool = True,
) -> Optional[pa.Table]:
    """Runs a Monte Carlo sweep, as ``touchdown sweep`` does, and returns its table.

    Args:
        scenario: A ``Scenario``, the path of a scenario file, or None for the default.
        samples: Number of samples, a whole number from 1 to 2^63 - 1 (``100_000``,
            ``1e5``, or a string as ``--samples`` takes it: ``"1e5"``, ``"2.5e5"``;
            default: the scenario's ``samples``, or the rows of ``inputs``).
        seed: The sweep's seed, 0 to 2^63 - 1 (default: the scenario's).
        threads: Worker threads, 1 to 1024 (default: one per core; a Python law is
            called by one worker at a time, for the hundreds of landers it holds at the
            instant, while the others step theirs).
        design: ``"independent"``, ``"sobol-sequence"`` or ``"sobol-indices"`` (default:
            the scenario's).
        inputs: Your own inputs, one sample per row: a path (CSV, Arrow or Parquet) or
            any table (pyarrow, polars, pandas), its columns named as the sweep's input
            columns. A table in memory is written to a private temporary file for the run
            and removed after it (messages call it "inputs (the table given)"); to
            ``trace`` a row of such a sweep, give ``inputs=`` the same table again.
        keep_columns: Pass the other columns of ``inputs`` through to the output.
        out: Also write the sweep to this file (Arrow, or Parquet by its extension or
            ``format``), as ``touchdown sweep --out`` does: under its name only when
            complete.
        format: ``"arrow"`` or ``"parquet"`` for ``out``.
        kernel: ``"auto"`` (the widest SIMD kernel the CPU runs), ``"avx512"``, ``"avx2"``
            or ``"portable"``.
        progress: Show a progress bar (tqdm where installed); default: on a terminal or in
            Jupyter.
        table: Return the table (held in memory: about 550 bytes a sample of the default
            scenario). ``table=False`` with ``out=`` writes the file only, in the command
            line's bounded memory, and returns None.

    Returns:
        The sweep as a ``pyarrow.Table``, one row per sample in sample order, its schema
        metadata that of the file (``pl.from_arrow(table)`` makes a polars frame); None
        with ``table=False``.

    Raises:
        ScenarioError: The scenario is refused.
        ValueError: A count or seed out of its range, or not a whole number (the message
            names the argument and the range).
        TouchdownError: Any other bad input, with the command line's message.
        KeyboardInterrupt: Ctrl-C (or a law that raised it) stopped the sweep; its message
            says where the rows done are. Nothing half-written is left under ``out``: the
            rows done are in ``OUT.interrupted``, a valid file that ``touchdown sweep
            --resume OUT`` finishes.
    """
    text = _scenario_text(scenario)
    with _inputs_path(inputs) as inputs_path:
        run = _touchdown.SweepRun(
            text,
            samples=samples,
            seed=seed,
            threads=threads,
            design=design,
            inputs=inputs_path,
            keep_columns=keep_columns,
            out=None if out is None else os.fspath(out),
            format=format,
            kernel=kernel,
            keep=table,
        )
        bar = _Bar(run.total, progress)
        try:
            while not run.wait(0.1):
                bar.update(run.done)
        except BaseException as stopped:
            # Ctrl-C (or any exception) while waiting: stop the workers, leave the file
            # valid and under the name of an interrupted sweep, and go on raising; a
            # KeyboardInterrupt says where the rows done are (or that none were kept).
            run.stop()
            while not run.wait(0.5):
                pass
            bar.close()
            try:
                run.result()
                where = f"the sweep was over: its file is {run.out}" if run.out else None
            except KeyboardInterrupt as said:
                where = str(said)
            except BaseException:
                where = None
            if isinstance(stopped, KeyboardInterrupt) and where and not stopped.args:
                stopped.args = (where,)
            raise
        bar.update(run.done)
        bar.close()
        reader = run.result()
        return None if reader is None else reader.read_all()


@dataclasses.dataclass
class Trace:
    """One sample run with the reference model, as ``touchdown trace`` runs it.

    Attributes:
        table: Its time history, one row per step (or per ``every`` steps) and last the
            state at the decision, as the trace file holds it (``pyarrow.Table`` with the
            file's metadata).
        text: What ``touchdown trace`` prints of it: the inputs and the results.
    """

    table: pa.Table
    text: str

    @property
    def metadata(self) -> Dict[str, str]:
        """The trace's provenance and results (``touchdown.outcome``, ...), decoded."""
        return {k.decode(): v.decode() for k, v in (self.table.schema.metadata or {}).items()}

    @property
    def outcome(self) -> str:
        """How the touchdown ended: stable, tipped, sliding, bouncing, held or diverged."""
        return self.metadata["touchdown.outcome"]

    def __str__(self) -> str:
        return self.text


def _sweep_metadata(table: Any) -> Dict[str, str]:
    """The schema metadata of a sweep held in memory, decoded; refused where there is none
    (a polars frame drops it)."""
    schema = getattr(table, "schema", None)
    meta = getattr(schema, "metadata", None) if isinstance(schema, pa.Schema) else None
    if not meta or b"touchdown.scenario" not in meta:
        raise TouchdownError(
            f"a {type(table).__name__} without a sweep's metadata: give the pyarrow.Table "
            f"that touchdown.sweep returned, or the sweep's file (a polars or pandas frame "
            f"does not keep the metadata)"
        )
    return {k.decode(): v.decode() for k, v in meta.items()}


def trace(
    source: Any = None,
    sample: Whole = 0,
    *,
    seed: Optional[Whole] = None,
    every: Whole = 1,
    inputs: Any = None,
) -> Trace:
    """Runs one sample in full detail with the reference model, as ``touchdown trace``.

    Args:
        source: What the sample is drawn from: a ``Scenario``, a scenario file (``.toml``),
            None for the default scenario, or a sweep: its file (Arrow or Parquet) or the
            ``pyarrow.Table`` that ``sweep`` returned, whose row ``sample`` the trace runs
            exactly.
        sample: The sample's index, from 0 (an int, or a string as ``--sample`` takes it).
        seed: The seed, 0 to 2^63 - 1 (a scenario only; a sweep has its own).
        every: One row every ``every`` steps, from 1.
        inputs: The table of inputs the sample's row comes from (a path or a table).

    Returns:
        A ``Trace``: its time history as a ``pyarrow.Table`` and what the command prints.
    """
    kwargs: Dict[str, Any] = {"every": every}
    with _inputs_path(inputs) as inputs_path:
        kwargs["inputs"] = inputs_path
        if source is None or isinstance(source, Scenario):
            kwargs.update(scenario_toml=_scenario_text(source), seed=seed)
        elif isinstance(source, (str, os.PathLike)):
            if Path(source).suffix.lower() == ".toml":
                kwargs.update(scenario_toml=_scenario_text(source), seed=seed)
            else:
                kwargs["sweep"] = os.fspath(source)
        else:
            kwargs["metadata"] = _sweep_metadata(source)
        if seed is not None and "scenario_toml" not in kwargs:
            raise TouchdownError("seed: a sweep's sample has the sweep's seed; drop seed=")
        try:
            text, reader = _touchdown.trace(sample, **kwargs)
        except TouchdownError as e:
            e.args = tuple(_GONE_TABLE.sub(_GONE_TABLE_SAYS, a) if isinstance(a, str) else a for a in e.args)
            raise
        return Trace(table=reader.read_all(), text=text)


def _report_source(source: Any) -> Dict[str, Any]:
    """The arguments naming a sweep for the report: its file, or its table in memory."""
    if isinstance(source, (str, os.PathLike)):
        return {"path": os.fspath(source)}
    _sweep_metadata(source)
    return {"table": source}


def report(source: Any, *, slope_distribution: Optional[str] = None) -> Dict[str, Any]:
    """What ``touchdown report`` says of a sweep, as data (the JSON of ``report --json``).

    Args:
        source: The sweep: its file (Arrow or Parquet) or the ``pyarrow.Table`` that
            ``sweep`` returned.
        slope_distribution: The outcome shares on a terrain of this distribution of slopes
            too (``"rayleigh:12"``, ``"uniform:0:30"``, ``"normal:20:8"``,
            ``"exponential:9"`` or a CSV file of bins), as ``--slope-distribution``.

    Returns:
        A dict: ``provenance``, ``outcomes`` (per outcome ``count``, ``share`` and its 95 %
        Wilson interval ``low``, ``high``), ``allowable_slope`` (per 45 deg sector),
        ``peak_loads``, ``exceedance`` (design values at 99 % and 99.9 %), and where the
        sweep has them ``gear``, ``stable_within_limits``, ``thrust``, ``release`` and
        ``terrain``. Numbers are unrounded; a value that cannot be given is None.
    """
    return json.loads(_touchdown.report(slope_distribution=slope_distribution, json=True, **_report_source(source)))


def report_markdown(source: Any, *, slope_distribution: Optional[str] = None) -> str:
    """The Markdown that ``touchdown report`` prints of a sweep (its file or its table)."""
    return _touchdown.report(slope_distribution=slope_distribution, json=False, **_report_source(source))
