"""The compile cache tells the scheduling process what it holds without code generation (issue
12): the structure of inputs seen before is remembered under a digest of the inputs, and a
structure compiled before is marked. A changed input must miss; a stale memo must never make a
run use other code than its own."""

import json
import os
import subprocess
import sys
from pathlib import Path

from mbds.campaign import known_structures as known
from mbds.campaign.plan import expand
from mbds.campaign.run import warm_up_first
from mbds.campaign.structures import Structures, structure
from mbds.expr.cache import source_hash
from mbds.expr.codegen import generate_source
from mbds.io.folder import read_model_files
from mbds.model.load import load_model
from tests.campaign.models import two_mass

ROOT = Path(__file__).resolve().parents[2]
TWO_VARIANTS = "c'gravity = 9.81, 5\n"


def test_the_digest_follows_every_input_and_nothing_else(tmp_path):
    job = two_mass(tmp_path / "a", TWO_VARIANTS)
    plan = expand(job)
    files = read_model_files(plan.job.world_path())
    digest = known.input_digest(files)
    copy = two_mass(tmp_path / "b", TWO_VARIANTS)
    assert known.input_digest(read_model_files(expand(copy).job.world_path())) == digest  # the folder is no input
    first, second = plan.variants
    assert len({digest, known.input_digest(files, first), known.input_digest(files, second)}) == 3
    hv = next(copy.parent.glob("*.hv"))
    hv.write_text(hv.read_text() + "\n")  # one byte more in one file
    assert known.input_digest(read_model_files(expand(copy).job.world_path())) != digest


def test_a_changed_input_misses_and_finds_its_own_structure(tmp_path, cache):
    job = two_mass(tmp_path, None)
    files = read_model_files(job.parent)
    key = structure(files)
    assert known.remembered(known.input_digest(files)) == key == load_model(job.parent).compiled.source_hash
    hv = next(job.parent.glob("*.hv"))
    hv.write_text(hv.read_text().replace("-(c'gravity", "-(2*c'gravity"))  # other equations: other code
    changed = read_model_files(job.parent)
    assert known.remembered(known.input_digest(changed)) is None
    assert structure(changed) == source_hash(generate_source(load_model(job.parent, compile=False).expressions)) != key


def test_a_stale_memo_never_gives_a_run_other_code(tmp_path, cache):
    job = two_mass(tmp_path, None)
    files = read_model_files(job.parent)
    truth = load_model(job.parent).compiled.source_hash
    wrong = "0" * len(truth)
    known.remember(known.input_digest(files), wrong)  # a memo pointing elsewhere
    assert structure(files) == wrong  # the memo is a hint for scheduling...
    assert load_model(job.parent).compiled.source_hash == truth  # ...a run generates its own code
    structures = Structures(expand(job))
    assert structures.make_ready(None)  # "wrong" is not compiled: the model is run for no time here
    assert known.compiled(truth)  # what ran is the model's own structure, now marked


def test_the_compiled_mark(tmp_path, cache):
    key = load_model(ROOT / "campaigns" / "2mass").compiled.source_hash
    marker = cache / f"mbds_model_{key}.ready"
    marker.unlink(missing_ok=True)
    assert not known.compiled(key)
    known.mark_compiled(key)
    assert known.compiled(key)
    other = json.loads(marker.read_text()) | {"numba": "0.0.0"}
    marker.write_text(json.dumps(other))
    assert not known.compiled(key)  # another numba compiled it
    known.mark_compiled(key)
    assert known.compiled(key)
    index = sorted((cache / "__pycache__").glob(f"mbds_model_{key}.mass_matrix-*.nbi"))
    moved = index[0].rename(index[0].with_suffix(".away"))
    assert not known.compiled(key)  # numba's index of the mass matrix is gone
    moved.rename(index[0])
    module = cache / f"mbds_model_{key}.py"
    os.utime(module, (marker.stat().st_mtime + 10,) * 2)
    assert not known.compiled(key)  # the module is newer than the mark: numba's code is stale
    assert not known.compiled("f" * len(key))


def test_a_warm_cache_warms_up_without_sympy_or_numba(tmp_path, cache):
    """The scheduling process of a campaign whose model was compiled before asks the cache."""
    job = two_mass(tmp_path, TWO_VARIANTS)
    assert warm_up_first(expand(job)).count == 1  # remembers and marks
    code = ("import sys\nfrom mbds.campaign.plan import expand\nfrom mbds.campaign.run import warm_up_first\n"
            "print(warm_up_first(expand(sys.argv[1])).count, "
            "' '.join(m for m in ('sympy', 'numba') if m in sys.modules) or '-')")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code, str(job)], capture_output=True, text=True, env=env, check=True)
    assert done.stdout.split() == ["1", "-"]
