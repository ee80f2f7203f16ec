"""rbcflow from Python: load and edit cases, drive runs step by step, read results.

Thin wrappers over the compiled module _rbcflow, which calls the same code as the rbcflow
command line (the scenario layer): a Simulation writes its output directory exactly as
`rbcflow run` does, Case.check() reports exactly what `rbcflow check` reports. See
docs/python.md.

    import rbcflow
    case = rbcflow.load_case("data/cases/capsule_shear.toml")
    case["time"]["end"] = 0.5
    sim = rbcflow.Simulation(case, out="out/shear")
    sim.run()
    run = rbcflow.read_run("out/shear")
"""

import collections.abc
import copy
import os

from ._rbcflow import CaseError, RunError
from . import _rbcflow

__all__ = ["Case", "CaseError", "RunError", "Simulation", "Run", "load_case", "read_run"]


class Case(collections.abc.MutableMapping):
    """A case file as nested dicts: case["time"]["end"] = 0.5; keys as in the TOML file."""

    def __init__(self, data, source="case.toml", text=None):
        self._data = data
        # Names the case in messages; relative paths in it (vessel.path) start from its folder.
        self.source = os.fspath(source)
        # The file's own text while the case is unchanged: messages then give the file's lines.
        self._text, self._as_read = text, copy.deepcopy(data) if text is not None else None

    @classmethod
    def from_dict(cls, d, source="case.toml"):
        """A case from a dict of tables (copied), validated as a case file is."""
        data = copy.deepcopy(dict(d))
        _rbcflow._dict_from_toml(_rbcflow._toml_from_dict(data), os.fspath(source))
        return cls(data, source)

    def __getitem__(self, key):
        return self._data[key]

    def __setitem__(self, key, value):
        self._data[key] = value

    def __delitem__(self, key):
        del self._data[key]

    def __iter__(self):
        return iter(self._data)

    def __len__(self):
        return len(self._data)

    def __repr__(self):
        return "rbcflow.Case(%r, source=%r)" % (self._data, self.source)

    def to_dict(self):
        """A deep copy of the case's tables."""
        return copy.deepcopy(self._data)

    def toml(self):
        """The case as TOML text (keys sorted)."""
        return _rbcflow._toml_from_dict(self._data)

    def save(self, path):
        """Writes the case as a TOML file."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.toml())

    def _source_text(self):
        """(text, name) to hand to the parser: the file as read while unchanged (its line
        numbers), else the case written anew, named "<source> (as edited)" (lines of toml())."""
        if self._text is not None and self._data == self._as_read:
            return self._text, self.source
        return self.toml(), self.source + " (as edited)"

    def check(self):
        """Everything `rbcflow check` validates (the vessel meshed, the cells placed and checked);
        raises CaseError with the file, line and key named."""
        _rbcflow._check(*self._source_text())


def load_case(path):
    """Reads a case file; raises CaseError (naming the file, line and key) for a bad one."""
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise CaseError("%s: cannot read the case file (%s)" % (path, e.strerror)) from None
    return Case(_rbcflow._dict_from_toml(text, path), path, text)


class Simulation:
    """A run of a case, driven step by step; its output directory is written exactly as
    `rbcflow run` writes it. A directory holding another run is refused (CaseError) unless
    overwrite=True. Ctrl-C stops between steps, leaving every finished step written."""

    def __init__(self, case, out, overwrite=False, _sim=None):
        if _sim is None:
            if not isinstance(case, Case):
                case = Case.from_dict(case)
            _sim = _rbcflow._Simulation(*case._source_text(), os.fspath(out), overwrite)
        self._sim = _sim

    @classmethod
    def from_checkpoint(cls, path, out, overwrite=False):
        """Continues the run that wrote checkpoint `path` (its case is stored in it) into `out`."""
        return cls(None, out, overwrite, _rbcflow._Simulation.from_checkpoint(os.fspath(path), os.fspath(out), overwrite))

    def step(self, n=1):
        """Takes n steps, each with its output (frames, rows, checkpoints when due)."""
        self._sim.step(n)

    def run(self):
        """Steps to the case's time.end, then writes the final frame, checkpoint and plot."""
        self._sim.run()

    @property
    def time(self):
        return self._sim.time

    @property
    def steps_done(self):
        return self._sim.steps_done

    @property
    def out(self):
        return self._sim.out

    def cell_nodes(self, i):
        """Cell i's points on its N x 2N grid, an (n, 3) array."""
        return self._sim.cell_nodes(i)

    def cell_centroids(self):
        """The cells' volume centroids, a (cells, 3) array."""
        return self._sim.cell_centroids()

    def cell_velocities(self):
        """Each cell's area-weighted mean surface velocity over the last step, (cells, 3); NaN
        before the first step."""
        return self._sim.cell_velocities()

    def diagnostics(self):
        """The diagnostics.csv columns written so far, a dict of 1-D arrays."""
        return _rbcflow._read_table(os.path.join(self.out, "diagnostics.csv"))

    def checkpoint(self, path):
        """Writes a checkpoint of the present state to `path`."""
        self._sim.checkpoint(os.fspath(path))


class Run:
    """A run's output directory read back (read_run)."""

    def __init__(self, path):
        self.path = os.fspath(path)
        self.diagnostics = _rbcflow._read_table(os.path.join(self.path, "diagnostics.csv"))
        cells = os.path.join(self.path, "cells.csv")
        self.cells = _rbcflow._read_table(cells) if os.path.exists(cells) else {}
        h5 = os.path.join(self.path, "rbcflow.h5")
        self._frames = _rbcflow._frames(self.path) if os.path.exists(h5) else []

    @property
    def frames(self):
        """The steps of the saved frames (XDMF output)."""
        return [step for step, _ in self._frames]

    @property
    def times(self):
        return [time for _, time in self._frames]

    def frame(self, step):
        """One frame: {"step", "time", "cells": {"points", "triangles", <fields>}, "wall": {...}}."""
        return _rbcflow._frame(self.path, int(step))


def read_run(path):
    """The diagnostics and cell rows (dicts of arrays) and the frames of a run's directory."""
    return Run(path)
