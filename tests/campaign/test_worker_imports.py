"""A campaign worker starts light (issue 12): importing what a worker runs (the executors, the
scheduling loop and the task runner) loads neither sympy, xarray, typer nor scipy, nor reads a
distribution's metadata (importlib.metadata: 40-60 ms at first, for a version); a task
imports the simulation layers when it runs, and never xarray or pandas (a whole chain run by a
worker process: tests/campaign/test_known_models.py)."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("sympy", "xarray", "typer", "scipy", "importlib.metadata")
WORKER_PATH = ("mbds.campaign.executors", "mbds.campaign.run", "mbds.campaign.tasks")


def test_worker_path_imports_no_heavy_package():
    code = (f"import sys\nimport {', '.join(WORKER_PATH)}\n"
            f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert result.stdout.split() == [], f"a worker imports {result.stdout.strip()} before any task runs"



def test_the_version_is_read_when_asked():
    """``import mbds`` does not read the distribution's metadata; ``mbds.__version__`` does, and
    gives what ``mbds --version`` prints."""
    code = ("import sys\nimport mbds\nprint('importlib.metadata' in sys.modules)\n"
            "print(mbds.__version__, 'importlib.metadata' in sys.modules)")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    printed = subprocess.run([str(Path(sys.executable).parent / "mbds"), "--version"], capture_output=True, text=True,
                             check=True).stdout.split()
    assert done.stdout.split() == ["False", printed[1], "True"]


def test_a_worker_rank_of_the_console_script_skips_the_command_line_parser():
    """``mpiexec -n N mbds-campaign run JOB``: every rank starts MPI first; a worker's path (the
    entry, MPI's world, the executors) imports neither typer nor rich. Help requests, other
    commands and a launcher of one rank take the parser's path at once."""
    code = ("import sys\nfrom mbds.cli import campaign_entry, mpi_world\nimport mbds.campaign.executors\n"
            "print(campaign_entry._launched_run(sys.argv[1:]), "
            "' '.join(m for m in ('typer', 'rich', 'sympy', 'xarray') if m in sys.modules) or '-')")

    def ask(size: str, *argv: str) -> list[str]:
        env = {**os.environ, "PYTHONPATH": str(ROOT), "PMI_SIZE": size, "PMI_RANK": "1"}
        done = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, env=env, check=True)
        return done.stdout.split()

    assert ask("4", "run", "wear.job") == ["True", "-"]
    assert ask("1", "run", "wear.job")[0] == "False"
    assert ask("4", "run", "--help")[0] == "False"
    assert ask("4", "status", "wear.job")[0] == "False"


def test_workers_import_what_tasks_need_when_told():
    """Rank 0 tells the workers the plan's task kinds before its warm-up: importing for a run
    loads the simulation layers and the kernel, so the first task does not wait for them; the
    outputs are written with netCDF4 alone, without xarray and pandas."""
    code = ("import sys\nfrom mbds.campaign.tasks import import_for\nimport_for(['prepare', 'run', 'wear'])\n"
            "print(' '.join(m for m in ('mbds.kernel.stepper', 'mbds.simulation.version_run', 'mbds.wear.version', "
            "'numba', 'netCDF4', 'xarray', 'pandas') if m in sys.modules))")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert done.stdout.split() == ["mbds.kernel.stepper", "mbds.simulation.version_run", "mbds.wear.version",
                                   "numba", "netCDF4"]


def test_a_worker_gets_ready_for_runs_before_rank_0_says_what_to_do():
    """While rank 0 expands the plan, a worker imports what runs of MBDS models need and lets
    numba set up its compiler's registries (which loading the first model would do); it stops
    at once when a message from rank 0 waits, so that a worker told to quit (a wrong option)
    quits without importing the simulation layers."""
    code = ("import sys\nfrom numba.core.registry import cpu_target\nfrom mbds.campaign.tasks import import_ahead\n"
            "import_ahead(lambda: sys.argv[1] == 'told')\n"
            "print(len(cpu_target.target_context._registries) > 0, "
            "' '.join(m for m in ('mbds.kernel.stepper', 'mbds.simulation.version_run', 'numba.np.arraymath', "
            "'scipy.linalg', 'sympy', 'xarray') if m in sys.modules) or '-')")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    def ahead(told: str) -> list[str]:
        return subprocess.run([sys.executable, "-c", code, told], capture_output=True, text=True, env=env,
                              check=True).stdout.split()

    assert ahead("waiting") == ["True", "mbds.kernel.stepper", "mbds.simulation.version_run", "numba.np.arraymath"]
    assert ahead("told") == ["False", "-"]


def test_numbas_numpy_support_is_loaded_without_scipy_linalg_and_blas_still_works():
    """numba's numpy support checks at import whether scipy's BLAS imports (scipy.linalg,
    0.15-0.35 s of a worker's start-up): importing for a run loads that support without it. A
    function compiled afterwards in the same process still calls BLAS through np.dot (the value
    against numpy's own), and scipy.linalg then imports as usual."""
    code = ("import sys\nfrom mbds.campaign.tasks import import_for\nimport_for(['prepare', 'run', 'wear'])\n"
            "print('numba.np.arraymath' in sys.modules, 'scipy.linalg' in sys.modules)\n"
            "import numba, numpy as np\n"
            "dot = numba.njit(lambda a, b: np.dot(a, b))\n"
            "a, b = np.arange(1.0, 7.0).reshape(2, 3), np.arange(2.0, 8.0).reshape(3, 2)\n"
            "print(np.array_equal(dot(a, b), a @ b), 'scipy.linalg' in sys.modules)")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert done.stdout.split() == ["True", "False", "True", "True"]


def test_a_worker_freezes_what_it_holds_after_loading_the_first_model(tmp_path):
    """The objects a worker holds once it has loaded the first model (imports, compiled code)
    live as long as it does: they are frozen out of the garbage collector's sweeps, even when the
    model fails to load (the prepare task reports that)."""
    code = ("import gc, sys\nfrom mbds.campaign.executors import _load_first\n"
            "_load_first(sys.argv[1], None)\nprint(gc.get_freeze_count() > 10000)")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code, str(tmp_path / "none.wld")], capture_output=True, text=True,
                          env=env, check=True)
    assert done.stdout.split() == ["True"]


def test_what_tasks_need_is_not_sympy():
    """A task of a model loaded before takes what sympy gave from the cache's record
    (tests/campaign/test_known_models.py): importing for every task kind loads no sympy."""
    code = ("import sys\nfrom mbds.campaign.tasks import import_for\nimport_for(['prepare', 'run', 'wear'])\n"
            "print(' '.join(m for m in ('sympy', 'typer') if m in sys.modules) or '-')")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert done.stdout.split() == ["-"]


def test_the_console_script_exits_with_the_commands_code_and_its_output_flushed(tmp_path):
    """The console script leaves without the interpreter's teardown: the exit code and everything
    printed must survive that."""
    console = Path(sys.executable).parent / "mbds-campaign"
    done = subprocess.run([str(console), "status", str(tmp_path / "none.job")], capture_output=True, text=True)
    assert done.returncode == 2 and "none.job" in done.stderr
    done = subprocess.run([str(console), "--help"], capture_output=True, text=True)
    assert done.returncode == 0 and "Run-in wear campaigns" in done.stdout


def test_workers_use_the_compile_cache_of_rank_0():
    """``run --campaign-cache`` sets the cache folder in rank 0 after the workers started: they
    learn it with the plan's task kinds, so that they load what rank 0 compiled."""
    code = ("import os\nfrom mbds.campaign.executors import prepare_worker\nfrom mbds.expr.cache import default_cache_dir\n"
            "prepare_worker([], '/campaign/.cache')\nprint(default_cache_dir())")
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MBDS_CACHE_DIR": "/elsewhere"}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert done.stdout.strip() == "/campaign/.cache"
