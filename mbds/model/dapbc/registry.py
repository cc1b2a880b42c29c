"""Registries of element classes by DAP_BC type name."""

from __future__ import annotations


def registrar(table: dict):
    """A class decorator factory: ``@register("rev")`` stores the class in ``table`` under that
    type name and sets its ``type_name``."""
    def register(name: str):
        def add(cls):
            cls.type_name = name
            table[name] = cls
            return cls
        return add
    return register
