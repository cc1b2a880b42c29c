"""Running one version of a model: buffers for the kernel, the run loop, and its results."""
