"""The expression language of MBDS models: parsing to sympy and compilation to numba functions.

- :mod:`mbds.expr.symbols`: the canonical sympy objects (coordinates, constants, mass properties).
- :mod:`mbds.expr.parse`: :func:`parse_expression`, text to sympy.
- :mod:`mbds.expr.codegen`: :func:`compile_model`, a model's equations to cached numba functions.

See ``docs/expressions.md`` for the language itself.
"""

from mbds.expr.codegen import (
    CompiledModel,
    DependentCoordinate,
    ModelExpressions,
    compile_model,
    generate_source,
)
from mbds.expr.parse import parse_expression

__all__ = [
    "CompiledModel",
    "DependentCoordinate",
    "ModelExpressions",
    "compile_model",
    "generate_source",
    "parse_expression",
]
