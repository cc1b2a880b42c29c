"""Outputs of runs: history.nc, the text files of the original program, watch post-processing."""
