"""Measured data (the measured-data CSV format) as numpy columns."""

from __future__ import annotations

import os
from typing import Mapping, Union

import numpy as np

from . import _hcm

PathLike = Union[str, "os.PathLike[str]"]

#: The format's columns, in order: ``run``, ``body`` (text), then ``time`` (s),
#: ``px``–``pz`` (m), ``qw``–``qz`` (–), ``vx``–``vz`` (m/s), ``wx``–``wz`` (rad/s),
#: ``fx``–``fz`` (N), ``tx``–``tz`` (N·m).
COLUMNS: tuple[str, ...] = tuple(_hcm.Dataset.columns())
NUMERIC: tuple[str, ...] = COLUMNS[2:]


class Dataset:
    """Runs of bodies' sampled motion and contact loads, one row per sample per body.

    ``data["fz"]`` is a column as a numpy array; ``data.columns`` all of them.
    """

    def __init__(self, compiled: _hcm.Dataset) -> None:
        self._dataset = compiled
        self._columns = None

    @classmethod
    def read_csv(cls, path: PathLike) -> "Dataset":
        """Reads a measured-data CSV file."""
        return cls(_hcm.Dataset.read_csv(os.fspath(path)))

    @classmethod
    def from_arrays(cls, columns: Mapping[str, object]) -> "Dataset":
        """A data set from columns by name: ``run``, ``body`` and ``time`` required,
        the other numeric columns optional (a channel left out is not sampled). Checked
        as a file is; messages name ``<arrays>`` and line r + 2 for row r."""
        unknown = sorted(set(columns) - set(COLUMNS))
        if unknown:
            raise _hcm.HcmError(
                f"from_arrays: unknown column(s) {', '.join(unknown)}; "
                f"the columns are: {', '.join(COLUMNS)}"
            )
        for required in ("run", "body", "time"):
            if required not in columns:
                raise _hcm.HcmError(f"from_arrays: the column `{required}` is required")
        time = np.asarray(columns["time"], dtype=np.float64).reshape(-1)
        rows = len(time)
        numeric = np.full((rows, len(NUMERIC)), np.nan)
        for i, name in enumerate(NUMERIC):
            if name in columns:
                numeric[:, i] = np.broadcast_to(np.asarray(columns[name], dtype=np.float64), (rows,))
        text = lambda name: [str(v) for v in np.broadcast_to(np.asarray(columns[name]), (rows,))]
        return cls(_hcm.Dataset.from_arrays(text("run"), text("body"), numeric))

    @classmethod
    def from_csv(cls, text: str, name: str = "<text>") -> "Dataset":
        """Reads measured-data CSV text; ``name`` names it in messages."""
        return cls(_hcm.Dataset.from_csv_text(text, name))

    @property
    def name(self) -> str:
        """What the data are called in messages and fit records: the file's path, or
        ``<arrays>``, ``<simulated>``, ``<S1>``, …."""
        return self._dataset.name

    def __reduce__(self):
        # Pickled as its CSV text (for multiprocessing, Ray, Dask).
        return (Dataset.from_csv, (self.to_csv(), self.name))

    def write_csv(self, path: PathLike) -> None:
        """Writes the measured-data CSV file (atomically)."""
        self._dataset.write_csv(os.fspath(path))

    def to_csv(self) -> str:
        """The CSV text ``write_csv`` writes."""
        return self._dataset.to_csv_text()

    @property
    def columns(self) -> dict[str, np.ndarray]:
        """Every column by name: ``run`` and ``body`` as string arrays, the rest float64."""
        if self._columns is None:
            runs, bodies, numeric = self._dataset.arrays()
            columns = {"run": np.array(runs, dtype=str), "body": np.array(bodies, dtype=str)}
            for i, name in enumerate(NUMERIC):
                columns[name] = numeric[:, i]
            self._columns = columns
        return self._columns

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(f"no column {name!r}; the columns are: {', '.join(COLUMNS)}") from None

    def __len__(self) -> int:
        return len(self.columns["time"])

    @property
    def runs(self) -> list[str]:
        """The run ids, in order."""
        return self._dataset.runs

    def to_pandas(self):
        """The columns as a pandas DataFrame (pandas must be installed)."""
        try:
            import pandas
        except ImportError as error:
            raise ImportError("to_pandas needs pandas: pip install pandas") from error
        return pandas.DataFrame(self.columns)

    def __repr__(self) -> str:
        return f"Dataset({len(self.runs)} run(s), {len(self)} rows)"
