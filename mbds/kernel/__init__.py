"""The numeric core: numba-compiled functions on numpy arrays and scalars only.

Nothing here imports xarray, sympy, mpi4py or typer; model numbers arrive as arguments.
"""
