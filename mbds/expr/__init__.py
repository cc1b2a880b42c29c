"""The expression language of MBDS models: parsing to sympy and compilation to numba functions.

- :mod:`mbds.expr.symbols`: the canonical sympy objects (coordinates, constants, mass properties).
- :mod:`mbds.expr.parse`: :func:`parse_expression`, text to sympy.
- :mod:`mbds.expr.codegen`: :func:`compile_model`, a model's equations to cached numba functions.

See ``docs/expressions.md`` for the language itself.
"""

__all__ = [
    "CompiledModel",
    "DependentCoordinate",
    "ModelExpressions",
    "compile_model",
    "generate_source",
    "parse_expression",
]
_LAZY = {name: "mbds.expr.codegen" for name in __all__[:-1]} | {"parse_expression": "mbds.expr.parse",
                                                                 "CompiledModel": "mbds.expr.compiled"}


def __getattr__(name: str):
    """The names of ``__all__``, imported on first use: importing a submodule that needs no
    sympy (:mod:`mbds.expr.cache`) does not import sympy."""
    if name in _LAZY:
        from importlib import import_module

        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'mbds.expr' has no attribute {name!r}")
