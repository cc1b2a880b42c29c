"""Outputs that stream: a run's samples go to its files part after part, memory does not grow
with the run's length, and callers get control back often, however sparse the samples."""

import tracemalloc

import numpy as np
import xarray as xr

from mbds.kernel import layout as K
from mbds.model.load import load_model
from mbds.simulation import version_run
from mbds.simulation.buffers import RunSettings
from mbds.simulation.run import RunStopped, simulate
from mbds.simulation.version_run import RunOptions, run_version
from mbds.simulation.versions import ensure_version
from tests.simulation.test_version_run import model_copy

WATCH_OPTIONS = ("2mass.wtc", "[mass1]", "[common]\ntimeConstant = 0.01\ncummulativeWork = 1\nwriteAveragedTDivN = 1\n"
                 "[mass1]")
SPARSE = ("2mass.wld", "maximumTimestep = 5e-4", "maximumTimestep = 5e-4\nwriteToHistoryMultipleOfMaximumTimestep = 100000")


def outputs(folder):
    """The text tables and the history's variables of version 000 of ``folder``."""
    version = folder / "000"
    texts = {name: (version / name).read_bytes() for name in ("data.txt", "watches.txt", "log.txt")}
    with xr.open_dataset(version / "history.nc") as ds:
        return texts, ds.drop_attrs().load()


def test_the_outputs_do_not_depend_on_the_parts_they_are_written_in(tmp_path, monkeypatch):
    """Decayed impulses, cumulative work and the running T/N ratio run over samples; written
    7 samples at a time they equal the outputs written 256 at a time, to the bit."""
    whole = model_copy(tmp_path / "a", edits=[WATCH_OPTIONS])
    run_version(ensure_version(whole, 0), RunOptions(duration=0.3))
    parts = model_copy(tmp_path / "b", edits=[WATCH_OPTIONS])
    monkeypatch.setattr(version_run, "PROGRESS_CHUNK", 7)
    run_version(ensure_version(parts, 0), RunOptions(duration=0.3))
    (texts_a, ds_a), (texts_b, ds_b) = outputs(whole), outputs(parts)
    assert texts_a == texts_b
    assert ds_a.identical(ds_b)
    assert ds_a["t_div_n"].values.any() and (np.diff(ds_a["work"].values, axis=0) >= 0).all()


def test_samples_handed_over_in_parts_equal_the_samples_kept(tmp_path):
    model = load_model(ensure_version(model_copy(tmp_path), 0), version=0)
    kept = simulate(model, RunSettings(0.3))
    parts = []
    handed = simulate(model, RunSettings(0.3, passes_per_call=13), on_samples=parts.append, chunk=5)
    assert len(handed.time) == 0 and len(parts) > len(kept.time) / 5
    for name in ("time", "q", "u", "a", "energy", "lost", "drive", "watches"):
        np.testing.assert_array_equal(np.concatenate([getattr(p, name) for p in parts]), getattr(kept, name))
    np.testing.assert_array_equal(handed.state.clock, kept.state.clock)


def test_the_caller_gets_control_back_between_sparse_samples(tmp_path):
    """With one sample at the start and the next 50 s later, the stepper still returns every
    passes_per_call passes of its loop: progress is looked at, and a stop takes effect, long
    before the next sample."""
    model = load_model(ensure_version(model_copy(tmp_path, edits=[SPARSE]), 0), version=0)
    calls = []
    result = simulate(model, RunSettings(0.5, passes_per_call=50), progress=calls.append)
    assert len(result.time) == 1 and result.complete and result.state.clock[K.T] == 0.5
    assert len(calls) >= result.state.clock[K.STEPS] / 50

    def stop(t):
        if t > 0.1:
            raise RunStopped("enough")

    stopped = simulate(model, RunSettings(0.5, passes_per_call=50), progress=stop)
    assert stopped.stopped == "enough" and 0.1 < stopped.state.clock[K.T] <= 0.1 + 50 * 5e-4  # 50 passes at most
    assert len(stopped.time) == 1


def peak_bytes(folder, duration):
    tracemalloc.start()
    run_version(ensure_version(folder, 0), RunOptions(duration=duration))
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def test_memory_does_not_grow_with_the_length_of_the_run(tmp_path):
    """A sample every step: a run 8 times as long (8 times the samples) needs about the same
    memory (peak of what Python allocates, numpy arrays included: about 0.7 MB)."""
    every_step = ("2mass.wld", "maximumTimestep = 5e-4", "maximumTimestep = 5e-4\nwriteToHistoryEachTimeStep = 1")
    peak_bytes(model_copy(tmp_path / "warm", edits=[every_step]), 0.05)  # compiled, imported
    short = peak_bytes(model_copy(tmp_path / "short", edits=[every_step]), 0.5)
    long = peak_bytes(model_copy(tmp_path / "long", edits=[every_step]), 4.0)
    with xr.open_dataset(tmp_path / "long" / "2mass" / "000" / "history.nc") as ds:
        samples = ds.sizes["time"]
    assert samples > 8000
    assert long < 1.5 * short, (short, long, samples)  # the long run's samples alone take 2.5 MB
