"""Running one version of a model: version folders, buffers for the kernel, the run loop, outputs."""
