"""Analyses by name: each takes a system and its settings and calls its kernel."""

from mbds.analysis.registry import ANALYSES, analysis, register_analysis

__all__ = ["ANALYSES", "analysis", "register_analysis"]
