#!/bin/sh
# Run a campaign on this machine with MPI: workflows/local.sh wear.job [workers]
#
# Starts workers + 1 ranks (default 2 workers: mpiexec -n 3). Rank 0 only schedules: it hands
# tasks out, waits for their results and writes the ledger, so it needs almost no CPU and the
# workers get one core each; on a two-core laptop, 3 ranks keep both cores busy with runs.
# Running it again resumes the campaign from its ledger.
#
# The interpreter is the one of `python` on PATH (an activated virtual environment), or
# $MBDS_PYTHON; mpiexec is the one beside it (the mpich wheel's), or $MBDS_MPIEXEC.
set -eu
if [ $# -lt 1 ]; then
    echo "usage: $0 JOB_FILE [WORKERS]" >&2
    exit 2
fi
job=$1
workers=${2:-2}
python=${MBDS_PYTHON:-$(command -v python)}
mpiexec=${MBDS_MPIEXEC:-$(dirname "$python")/mpiexec}
[ -x "$mpiexec" ] || mpiexec=mpiexec
export OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 NUMBA_NUM_THREADS=1
exec "$mpiexec" -n "$((workers + 1))" "$python" -m mpi4py -m mbds.cli.campaign run "$job"
