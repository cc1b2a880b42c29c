"""Wear between versions: worn shapes and updated constants of the next version (pure numerics)."""
